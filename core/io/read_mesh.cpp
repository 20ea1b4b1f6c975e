#include "core/io/read_mesh.hpp"

#include <string>

#include "core/io/mesh_document.hpp"

namespace meshmark {

namespace {

DocumentReadOptions document_options(const ReadOptions& options) {
  DocumentReadOptions d;
  d.limits = options;
  d.for_writing = false;  // only the mesh is wanted
  return d;
}

ReadResult result_of(const MeshDocument& document) {
  ReadResult r;
  r.mesh = document.scene();
  r.polygons_triangulated = document.polygons_triangulated();
  return r;
}

}  // namespace

ReadResult read_mesh_from_memory(std::string_view bytes, MeshFormat format, const ReadOptions& options,
                                 std::string_view source_name) {
  return result_of(*read_document(std::string(bytes), format, document_options(options), std::string(source_name)));
}

ReadResult read_mesh(const std::filesystem::path& path, const ReadOptions& options) {
  return result_of(*read_document_file(path, document_options(options)));
}

}  // namespace meshmark
