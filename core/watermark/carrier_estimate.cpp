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

// The k-th of a fixed sequence of ±1 patterns (a 64-bit linear congruential generator's top bits).
Eigen::VectorXd probe_pattern(Eigen::Index size, std::uint64_t seed) {
  Eigen::VectorXd r(size);
  std::uint64_t state = seed * 0x9e3779b97f4a7c15ull + 1;
  for (Eigen::Index k = 0; k < size; ++k) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    r[k] = (state >> 33) & 1 ? 1.0 : -1.0;
  }
  return r;
}

// Per-carrier Hutchinson probes of diag(AᵀA) taken within a group: carriers of one band
// overlap little, so a few probes see each one's own scale (a carrier the vertices sample
// thinly gets a small one and its own step).
constexpr int kDiagonalProbes = 4;

}  // namespace

Eigen::VectorXd CarrierEstimator::probed_diagonal(const std::vector<char>& in_group, double floor) const {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(carriers_), mask(carriers_);
  for (Eigen::Index k = 0; k < carriers_; ++k) mask[k] = in_group[static_cast<std::size_t>(k)] ? 1 : 0;
  for (int j = 0; j < kDiagonalProbes; ++j) {
    const Eigen::VectorXd r = probe_pattern(carriers_, static_cast<std::uint64_t>(j)).cwiseProduct(mask);
    sum += r.cwiseProduct(gram(r));
  }
  return (sum / kDiagonalProbes).cwiseMax(floor);
}

const Eigen::VectorXd& CarrierEstimator::group_diagonal() const {
  // One group (no grouping): its mean by one probe. Several: each group's mean likewise, and
  // within each group every carrier's own value by a few probes (at least a tenth of the mean).
  std::call_once(measured_, [&] {
    group_diagonal_ = Eigen::VectorXd::Ones(carriers_);
    if (carriers_ == 0) return;
    const int groups = *std::max_element(groups_.begin(), groups_.end()) + 1;
    double total = 0;
    for (int g = 0; g < groups; ++g) {
      std::vector<char> in_group(groups_.size());
      for (std::size_t k = 0; k < groups_.size(); ++k) in_group[k] = groups_[k] == g;
      const auto members = std::count(in_group.begin(), in_group.end(), 1);
      if (members == 0) continue;
      Eigen::VectorXd r = Eigen::VectorXd::Zero(carriers_);
      for (Eigen::Index k = 0; k < carriers_; ++k)
        if (in_group[static_cast<std::size_t>(k)]) r[k] = probe_sign(k);
      const double sum = r.dot(gram(r)), mean = std::max(sum / static_cast<double>(members), 1e-300);
      total += sum;
      const Eigen::VectorXd own = groups > 1 ? probed_diagonal(in_group, 0.1 * mean) : Eigen::VectorXd();
      for (Eigen::Index k = 0; k < carriers_; ++k)
        if (in_group[static_cast<std::size_t>(k)]) group_diagonal_[k] = groups > 1 ? own[k] : mean;
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
Eigen::VectorXd CarrierEstimator::estimate(const Eigen::VectorXd& matched, double relative) const {
  if (relative == 0) return matched;
  const double mu = regularization(relative);
  const Eigen::VectorXd inverse = (group_diagonal().array() + mu).inverse().matrix();
  Eigen::VectorXd c = matched.cwiseProduct(inverse), r = matched - (gram(c) + mu * c), z = r.cwiseProduct(inverse),
                  p = z;
  double rz = r.dot(z);
  const double stop = solve_.relative_residual2 * matched.squaredNorm();
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

std::vector<Eigen::VectorXd> CarrierEstimator::estimates(const Eigen::VectorXd& matched,
                                                         const std::vector<double>& relatives) const {
  std::vector<Eigen::VectorXd> out(relatives.size());
  const bool one_group = std::all_of(groups_.begin(), groups_.end(), [](int g) { return g == 0; });
  std::vector<double> mus;
  for (std::size_t i = 0; i < relatives.size(); ++i) {
    if (relatives[i] == 0) out[i] = matched;
    else if (!one_group) out[i] = estimate(matched, relatives[i]);
    else mus.push_back(regularization(relatives[i]));
  }
  if (mus.empty()) return out;
  std::vector<Eigen::VectorXd> solved = multi_shift(matched, mus);
  for (std::size_t i = 0, k = 0; i < relatives.size(); ++i)
    if (out[i].size() == 0 && relatives[i] != 0) out[i] = std::move(solved[k++]);
  return out;
}

// CG on the least shift (AᵀA + μ₀I)c = x from c = 0; every other shift μ = μ₀ + σ has the
// residual ζ·r of the base's, and its own step lengths follow from ζ's recurrence
// (Jegerlehner 1996; van den Eshof & Sleijpen 2004). σ ≥ 0 keeps the ζ bounded by one.
std::vector<Eigen::VectorXd> CarrierEstimator::multi_shift(const Eigen::VectorXd& x,
                                                           const std::vector<double>& mus) const {
  const double mu0 = *std::min_element(mus.begin(), mus.end());
  const std::size_t shifts = mus.size();
  std::vector<Eigen::VectorXd> c(shifts, Eigen::VectorXd::Zero(carriers_)), p(shifts, x);
  std::vector<double> zeta(shifts, 1.0), zeta_before(shifts, 1.0);
  Eigen::VectorXd r = x, base_p = x;
  double rr = r.squaredNorm(), alpha_before = 1.0, beta_before = 0.0;
  const double stop = solve_.relative_residual2 * x.squaredNorm();
  const auto converged = [&] {
    for (std::size_t s = 0; s < shifts; ++s)
      if (zeta[s] * zeta[s] * rr > stop) return false;
    return true;
  };
  for (int it = 0; it < solve_.max_iterations && !converged(); ++it) {
    const Eigen::VectorXd Ap = gram(base_p) + mu0 * base_p;
    const double alpha = rr / base_p.dot(Ap);
    std::vector<double> zeta_next(shifts);
    for (std::size_t s = 0; s < shifts; ++s) {
      const double sigma = mus[s] - mu0;
      zeta_next[s] =
          zeta[s] * zeta_before[s] * alpha_before /
          (alpha * beta_before * (zeta_before[s] - zeta[s]) + zeta_before[s] * alpha_before * (1.0 + sigma * alpha));
      c[s] += (alpha * zeta_next[s] / zeta[s]) * p[s];
    }
    r -= alpha * Ap;
    const double rr_next = r.squaredNorm(), beta = rr_next / rr;
    for (std::size_t s = 0; s < shifts; ++s) {
      const double ratio = zeta_next[s] / zeta[s];
      p[s] = zeta_next[s] * r + (beta * ratio * ratio) * p[s];
    }
    base_p = r + beta * base_p;
    zeta_before = zeta, zeta = zeta_next;
    alpha_before = alpha, beta_before = beta, rr = rr_next;
  }
  return c;
}

}  // namespace meshmark
