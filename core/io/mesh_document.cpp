#include "core/io/mesh_document.hpp"

#include <Eigen/LU>
#include <fstream>
#include <iterator>

#include "core/io/document_readers.hpp"
#include "core/io/mesh_io_error.hpp"

namespace meshmark {

Mesh MeshDocument::scene() const {
  Eigen::Index vertices = positions_.rows(), faces = triangles_.rows();
  for (const FurtherInstance& instance : further_instances_) {
    vertices += instance.mesh.V.rows();
    faces += instance.mesh.F.rows();
  }
  Mesh out;
  out.V.resize(vertices, 3);
  out.F.resize(faces, 3);
  out.V.topRows(positions_.rows()) = positions_;
  out.F.topRows(triangles_.rows()) = triangles_;
  Eigen::Index v = positions_.rows(), f = triangles_.rows();
  for (const FurtherInstance& instance : further_instances_) {
    out.V.middleRows(v, instance.mesh.V.rows()) = instance.mesh.V;
    out.F.middleRows(f, instance.mesh.F.rows()) = instance.mesh.F.array() + static_cast<int>(v);
    v += instance.mesh.V.rows();
    f += instance.mesh.F.rows();
  }
  return out;
}

bool MeshDocument::add_companion(const std::string& uri, const std::string& source) {
  if (!companion_set_.insert(uri).second) return false;
  if (companion_set_.size() > kMaxCompanions)
    throw MeshLimitError(source + ": names more than " + std::to_string(kMaxCompanions) + " companion files");
  companions_.push_back(uri);
  return true;
}

Eigen::Matrix3d move_to_slot(const Eigen::Matrix3d& slot_world, const Eigen::Matrix3d& world) {
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(world);
  if (!lu.isInvertible()) return Eigen::Matrix3d::Zero();
  return slot_world * lu.inverse();
}

std::unique_ptr<MeshDocument> read_document(std::string bytes, MeshFormat format, const DocumentReadOptions& options,
                                            const std::string& source) {
  switch (format) {
    case MeshFormat::obj:
      return read_obj_document(std::move(bytes), options, source);
    case MeshFormat::off:
      return read_off_document(std::move(bytes), options, source);
    case MeshFormat::ply:
      return read_ply_document(std::move(bytes), options, source);
    case MeshFormat::stl:
      return read_stl_document(std::move(bytes), options, source);
    case MeshFormat::glb:
      return read_gltf_document(std::move(bytes), true, options, source);
    case MeshFormat::gltf:
      return read_gltf_document(std::move(bytes), false, options, source);
    case MeshFormat::threemf:
      return read_3mf_document(std::move(bytes), options, source);
  }
  throw MeshIoError(source + ": unknown mesh format");
}

std::string percent_decoded(std::string_view uri) {
  const auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out.push_back(static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2])));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

std::string read_file_bytes(const std::filesystem::path& path, std::size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshIoError(path.string() + ": cannot open the file for reading");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw MeshIoError(path.string() + ": cannot tell the file size: " + ec.message());
  if (size > max_bytes)
    throw MeshLimitError(path.string() + ": the file is " + std::to_string(size) + " bytes, above the limit of " +
                         std::to_string(max_bytes));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size)))
    throw MeshIoError(path.string() + ": cannot read the file");
  return bytes;
}

std::unique_ptr<MeshDocument> read_document_file(const std::filesystem::path& path, DocumentReadOptions options) {
  const MeshFormat format = mesh_format_from_path(path);
  if (!options.companion) {
    const std::filesystem::path folder = path.parent_path();
    const std::size_t limit = options.limits.max_file_bytes;
    options.companion = [folder, limit](const std::string& uri) {
      const std::string path = percent_decoded(uri);
      if (path.empty() || path.front() == '/' || path.find("..") != std::string::npos ||
          path.find(':') != std::string::npos)
        throw MeshIoError("the companion file '" + uri + "' is not a plain relative path beside the main file");
      return read_file_bytes(folder / path, limit);
    };
  }
  return read_document(read_file_bytes(path, options.limits.max_file_bytes), format, options, path.string());
}

}  // namespace meshmark
