#include "core/render/preview_mesh.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>

#include "core/mesh/vertex_normals.hpp"

namespace meshmark {

namespace {

template <typename T>
void put(std::string& out, T value) {
  static_assert(std::endian::native == std::endian::little, "PLY previews are written little-endian");
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

std::string header(const Mesh& mesh, bool with_displacement) {
  std::string h = "ply\nformat binary_little_endian 1.0\ncomment meshmark preview\n";
  h += "element vertex " + std::to_string(mesh.V.rows()) + "\n";
  h += "property float x\nproperty float y\nproperty float z\n";
  if (with_displacement) h += "property float displacement\n";
  h += "element face " + std::to_string(mesh.F.rows()) + "\n";
  h += "property list uchar uint vertex_indices\nend_header\n";
  return h;
}

}  // namespace

std::string write_preview_ply(const Mesh& mesh, const std::optional<std::vector<float>>& displacement) {
  if (displacement && static_cast<Eigen::Index>(displacement->size()) != mesh.V.rows())
    throw std::invalid_argument("preview: one displacement per vertex");
  std::string out = header(mesh, displacement.has_value());
  out.reserve(out.size() + static_cast<std::size_t>(mesh.V.rows()) * 16 + static_cast<std::size_t>(mesh.F.rows()) * 13);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    for (int k = 0; k < 3; ++k) put(out, static_cast<float>(mesh.V(v, k)));
    if (displacement) put(out, (*displacement)[static_cast<std::size_t>(v)]);
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out.push_back(3);
    for (int k = 0; k < 3; ++k) put(out, static_cast<std::uint32_t>(mesh.F(f, k)));
  }
  return out;
}

std::vector<float> normal_displacement_percent(const Mesh& original, const Vertices& marked) {
  if (marked.rows() != original.V.rows())
    throw std::invalid_argument("displacement: the copy has " + std::to_string(marked.rows()) +
                                " vertices where the original has " + std::to_string(original.V.rows()));
  const Vertices normals = vertex_normals(original.V, original.F);
  const double diagonal = (original.V.colwise().maxCoeff() - original.V.colwise().minCoeff()).norm();
  const double scale = diagonal > 0 ? 100.0 / diagonal : 0.0;
  std::vector<float> out(static_cast<std::size_t>(marked.rows()));
  for (Eigen::Index v = 0; v < marked.rows(); ++v)
    out[static_cast<std::size_t>(v)] =
        static_cast<float>((marked.row(v) - original.V.row(v)).dot(normals.row(v)) * scale);
  return out;
}

}  // namespace meshmark
