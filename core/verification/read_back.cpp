#include "core/verification/read_back.hpp"

#include "core/io/packaged_document.hpp"
#include "core/mesh/weld_positions.hpp"

namespace meshmark {

namespace {

Mesh welded_scene(const MeshDocument& document) {
  const Mesh scene = document.scene();
  return weld_positions(scene.V, scene.F).mesh;
}

}  // namespace

Mesh read_back(const DocumentFiles& files, MeshFormat format,
               const std::function<std::string(const std::string& uri)>& unchanged, const ReadOptions& limits) {
  DocumentReadOptions options;
  options.limits = limits;
  options.companion = [&](const std::string& uri) {
    auto written = files.find(uri);
    if (written == files.end()) written = files.find(percent_decoded(uri));
    return written != files.end() ? written->second : unchanged(uri);
  };
  return welded_scene(*read_document(files.at(""), format, options, "the marked copy"));
}

Mesh read_back(const std::string& bytes, MeshFormat format, const ReadOptions& limits) {
  DocumentReadOptions options;
  options.limits = limits;
  return welded_scene(PackagedDocument(bytes, format, options, "the marked copy").document());
}

}  // namespace meshmark
