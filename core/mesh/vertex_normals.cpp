#include "core/mesh/vertex_normals.hpp"

namespace meshmark {

Vertices vertex_normals(const Vertices& V, const Faces& F) {
  Vertices N = Vertices::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d area_normal = (b - a).cross(c - a);  // twice the area, along the normal
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += area_normal;
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double length = N.row(v).norm();
    if (length > 0) N.row(v) /= length;
  }
  return N;
}

Vertices face_normals(const Vertices& V, const Faces& F) {
  Vertices N(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a);
    const double length = n.norm();
    N.row(f) = length > 0 ? Eigen::RowVector3d(n / length) : Eigen::RowVector3d::Zero();
  }
  return N;
}

}  // namespace meshmark
