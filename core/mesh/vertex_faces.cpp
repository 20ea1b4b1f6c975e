#include "core/mesh/vertex_faces.hpp"

namespace meshmark {

VertexFaces vertex_faces(const Faces& F, Eigen::Index vertex_count) {
  VertexFaces result;
  result.offsets.assign(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++result.offsets[F(f, k) + 1];
  for (std::size_t v = 1; v < result.offsets.size(); ++v) result.offsets[v] += result.offsets[v - 1];
  result.faces.resize(static_cast<std::size_t>(3 * F.rows()));
  std::vector<int> cursor(result.offsets.begin(), result.offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) result.faces[cursor[F(f, k)]++] = static_cast<int>(f);
  return result;
}

}  // namespace meshmark
