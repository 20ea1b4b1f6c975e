#include "core/watermark/carrier_estimate.hpp"

#include <algorithm>
#include <cmath>

namespace meshmark {

int bits_for_tries(std::size_t count) {
  return count <= 1 ? 0 : static_cast<int>(std::ceil(std::log2(static_cast<double>(count))));
}

CarrierEstimator::CarrierEstimator(LinearMap forward, LinearMap adjoint, Eigen::Index carriers,
                                   CarrierSolveOptions solve)
    : forward_(std::move(forward)), adjoint_(std::move(adjoint)), carriers_(carriers), solve_(solve) {}

double CarrierEstimator::mean_diagonal() const {
  // Mean of diag(AᵀA) by one Hutchinson probe with a fixed sign pattern.
  std::call_once(measured_, [&] {
    Eigen::VectorXd r(carriers_);
    for (Eigen::Index k = 0; k < carriers_; ++k)
      r[k] = (static_cast<std::uint64_t>(k) * 2654435761u >> 7) & 1 ? 1.0 : -1.0;
    if (carriers_ > 0) mean_diagonal_ = std::max(r.dot(gram(r)) / static_cast<double>(carriers_), 1e-300);
  });
  return mean_diagonal_;
}

Eigen::VectorXd CarrierEstimator::estimate(const Eigen::VectorXd& x, double relative) const {
  if (relative == 0) return x;
  const double mu = regularization(relative);
  Eigen::VectorXd c = x / (mean_diagonal() + mu), r = x - (gram(c) + mu * c), p = r;
  double rr = r.squaredNorm();
  const double stop = solve_.relative_residual2 * x.squaredNorm();
  for (int it = 0; it < solve_.max_iterations && rr > stop; ++it) {
    const Eigen::VectorXd Ap = gram(p) + mu * p;
    const double a = rr / p.dot(Ap);
    c += a * p;
    r -= a * Ap;
    const double next = r.squaredNorm();
    p = r + (next / rr) * p;
    rr = next;
  }
  return c;
}

}  // namespace meshmark
