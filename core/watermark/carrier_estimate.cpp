#include "core/watermark/carrier_estimate.hpp"

#include <algorithm>
#include <cmath>

namespace meshmark {

int bits_for_tries(std::size_t count) {
  return count <= 1 ? 0 : static_cast<int>(std::ceil(std::log2(static_cast<double>(count))));
}

CarrierEstimator::CarrierEstimator(LinearMap forward, LinearMap adjoint, Eigen::Index carriers,
                                   CarrierSolveOptions solve, std::vector<int> groups)
    : forward_(std::move(forward)),
      adjoint_(std::move(adjoint)),
      carriers_(carriers),
      solve_(solve),
      groups_(groups.empty() ? std::vector<int>(static_cast<std::size_t>(carriers), 0) : std::move(groups)) {}

namespace {

// A fixed ±1 pattern: a Hutchinson probe that is the same on every run.
double probe_sign(Eigen::Index k) { return (static_cast<std::uint64_t>(k) * 2654435761u >> 7) & 1 ? 1.0 : -1.0; }

}  // namespace

const Eigen::VectorXd& CarrierEstimator::group_diagonal() const {
  // Each group's mean of diag(AᵀA) by one probe on its carriers alone; the overall mean with it.
  std::call_once(measured_, [&] {
    group_diagonal_ = Eigen::VectorXd::Ones(carriers_);
    if (carriers_ == 0) return;
    const int groups = *std::max_element(groups_.begin(), groups_.end()) + 1;
    double total = 0;
    for (int g = 0; g < groups; ++g) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(carriers_);
      Eigen::Index members = 0;
      for (Eigen::Index k = 0; k < carriers_; ++k)
        if (groups_[static_cast<std::size_t>(k)] == g) r[k] = probe_sign(k), ++members;
      if (members == 0) continue;
      const double sum = r.dot(gram(r));
      total += sum;
      for (Eigen::Index k = 0; k < carriers_; ++k)
        if (groups_[static_cast<std::size_t>(k)] == g)
          group_diagonal_[k] = std::max(sum / static_cast<double>(members), 1e-300);
    }
    mean_diagonal_ = std::max(total / static_cast<double>(carriers_), 1e-300);
  });
  return group_diagonal_;
}

double CarrierEstimator::mean_diagonal() const {
  group_diagonal();
  return mean_diagonal_;
}

// Conjugate gradients on (AᵀA + μI) c = x, preconditioned by each group's mean diagonal.
Eigen::VectorXd CarrierEstimator::estimate(const Eigen::VectorXd& x, double relative) const {
  if (relative == 0) return x;
  const double mu = regularization(relative);
  const Eigen::VectorXd inverse = (group_diagonal().array() + mu).inverse().matrix();
  Eigen::VectorXd c = x.cwiseProduct(inverse), r = x - (gram(c) + mu * c), z = r.cwiseProduct(inverse), p = z;
  double rz = r.dot(z);
  const double stop = solve_.relative_residual2 * x.squaredNorm();
  for (int it = 0; it < solve_.max_iterations && r.squaredNorm() > stop; ++it) {
    const Eigen::VectorXd Ap = gram(p) + mu * p;
    const double a = rz / p.dot(Ap);
    c += a * p;
    r -= a * Ap;
    z = r.cwiseProduct(inverse);
    const double next = r.dot(z);
    p = z + (next / rz) * p;
    rz = next;
  }
  return c;
}

}  // namespace meshmark
