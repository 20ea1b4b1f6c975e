#include "core/mesh/orientation.hpp"

namespace meshmark {

double signed_volume(const Vertices& V, const Faces& F) {
  if (V.rows() == 0) return 0;
  const Eigen::RowVector3d center = V.colwise().mean();
  double six_volume = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)) - center, b = V.row(F(f, 1)) - center, c = V.row(F(f, 2)) - center;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

Faces orient_outward(const Vertices& V, const Faces& F) {
  Faces out = F;
  if (signed_volume(V, F) < 0) out.col(1).swap(out.col(2));
  return out;
}

}  // namespace meshmark
