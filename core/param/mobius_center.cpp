#include "core/param/mobius_center.hpp"

#include <Eigen/Dense>

namespace meshmark {

Eigen::Vector3d mobius_transform(const Eigen::Vector3d& x, const Eigen::Vector3d& c) {
  const Eigen::Vector3d y = x + c;
  const Eigen::Vector3d z = (1.0 - c.squaredNorm()) * y / y.squaredNorm() + c;
  return z.normalized();  // on the sphere in exact arithmetic; renormalize the round-off
}

MobiusCenterResult mobius_center(Vertices& S, const Eigen::VectorXd& weights, const MobiusCenterOptions& options) {
  MobiusCenterResult result;
  const double total = weights.sum();
  for (; result.iterations < options.max_iterations; ++result.iterations) {
    const Eigen::Vector3d center = (S.transpose() * weights) / total;
    result.residual = center.norm();
    if (result.residual < options.tolerance) break;
    // Newton step on the centre of mass: its derivative in c at c = 0 is Σ w (2I − 2 x xᵀ).
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (Eigen::Index i = 0; i < S.rows(); ++i) {
      const Eigen::Vector3d x = S.row(i);
      J += weights[i] * (2.0 * Eigen::Matrix3d::Identity() - 2.0 * x * x.transpose());
    }
    Eigen::Vector3d c = -(J / total).ldlt().solve(center);
    if (c.norm() > 0.5) c *= 0.5 / c.norm();  // stay well inside the ball
    for (Eigen::Index i = 0; i < S.rows(); ++i) S.row(i) = mobius_transform(S.row(i).transpose(), c);
  }
  return result;
}

}  // namespace meshmark
