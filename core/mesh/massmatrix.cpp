#include "core/mesh/massmatrix.hpp"

namespace meshmark {

Eigen::VectorXd face_areas(const Vertices& V, const Faces& F) {
  Eigen::VectorXd area(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    area[f] = 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

Eigen::VectorXd vertex_areas(const Vertices& V, const Faces& F) {
  const Eigen::VectorXd area = face_areas(V, F);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(V.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) mass[F(f, k)] += area[f] / 3.0;
  return mass;
}

}  // namespace meshmark
