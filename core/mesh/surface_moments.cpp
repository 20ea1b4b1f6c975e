#include "core/mesh/surface_moments.hpp"

#include <Eigen/Eigenvalues>

namespace meshmark {

SurfaceMoments surface_moments(const Mesh& mesh) {
  // Over a triangle of area A: ∫x dA = A·(a+b+c)/3, ∫x xᵀ dA = A/12·(Σ v vᵀ + s sᵀ), s = a+b+c.
  double area = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    const double A = 0.5 * (b - a).cross(c - a).norm();
    const Eigen::Vector3d s = a + b + c;
    area += A;
    first += A / 3 * s;
    second += A / 12 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  SurfaceMoments m;
  if (!(area > 0)) return m;
  m.centroid = first / area;
  const Eigen::Matrix3d covariance = second / area - m.centroid * m.centroid.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  m.axes = eigen.eigenvectors().rowwise().reverse();
  m.variances = eigen.eigenvalues().reverse();
  return m;
}

}  // namespace meshmark
