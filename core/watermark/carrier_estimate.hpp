#pragma once
// Estimating carrier amplitudes s from a measured normal-displacement field t = A s + noise,
// where A (carriers → values at the vertices) is given as a pair of functions: the plain
// matched filter Aᵀ t, or the regularized least-squares estimate (AᵀA + μ d I)⁻¹ Aᵀ t, with d
// the mean of diag(AᵀA). The matched filter is best in heavy noise; a small μ undoes the overlap
// of neighbouring carriers, best in light noise. Both are linear in t and ignore the key.

#include <Eigen/Core>
#include <functional>
#include <mutex>
#include <vector>

namespace meshmark {

using LinearMap = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

/// The conjugate-gradient solve behind a regularized estimate: loose, because the estimate only
/// feeds correlations.
struct CarrierSolveOptions {
  int max_iterations = 60;           ///< CG steps at most
  double relative_residual2 = 1e-6;  ///< stop when ‖r‖² ≤ this × ‖Aᵀt‖²
};

class CarrierEstimator {
 public:
  /// `forward`: carriers → vertex values (A); `adjoint`: vertex values → carriers (Aᵀ).
  /// `groups` (carrier → group, e.g. its band; empty: one group) precondition the solve: each
  /// carrier's diag(AᵀA) is probed within its group, so bands of very different scale, and
  /// carriers the measurements sample thinly, converge alike.
  CarrierEstimator(LinearMap forward, LinearMap adjoint, Eigen::Index carriers, CarrierSolveOptions solve = {},
                   std::vector<int> groups = {});

  /// Aᵀ t, computed once per measurement.
  Eigen::VectorXd matched(const Eigen::VectorXd& t) const { return adjoint_(t); }

  /// μ = relative · d; relative = 0 returns `matched` itself.
  Eigen::VectorXd estimate(const Eigen::VectorXd& matched, double relative) const;

  /// The estimate for each of `relatives`, in their order. With one group the preconditioner is
  /// a scalar, and the shifted systems share one Krylov space: a multi-shift CG solves them all
  /// for the applications of AᵀA the most regularized-least one takes alone.
  std::vector<Eigen::VectorXd> estimates(const Eigen::VectorXd& matched, const std::vector<double>& relatives) const;

  /// The μ a relative regularization stands for (d measured by one probe of AᵀA).
  double regularization(double relative) const { return relative * mean_diagonal(); }

 private:
  Eigen::VectorXd gram(const Eigen::VectorXd& s) const { return adjoint_(forward_(s)); }
  // Measured on first use: a matched filter alone (a copy read back in place) never needs it.
  double mean_diagonal() const;
  const Eigen::VectorXd& group_diagonal() const;  // per carrier: the preconditioner's diag(AᵀA)
  Eigen::VectorXd probed_diagonal(const std::vector<char>& in_group, double floor) const;
  std::vector<Eigen::VectorXd> multi_shift(const Eigen::VectorXd& x, const std::vector<double>& mus) const;
  LinearMap forward_, adjoint_;
  Eigen::Index carriers_;
  CarrierSolveOptions solve_;
  std::vector<int> groups_;
  mutable std::once_flag measured_;
  mutable Eigen::VectorXd group_diagonal_;
  mutable double mean_diagonal_ = 1;
};

/// Bits the false-alarm bound must add for trying `count` estimates (a union over them).
int bits_for_tries(std::size_t count);

}  // namespace meshmark
