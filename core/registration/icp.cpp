#include "core/registration/icp.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/util/parallel_for.hpp"

namespace meshmark::registration {

namespace {

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

// One trimmed point-to-plane step with scale (unless `hold_scale`); returns the RMS of the kept
// plane distances and updates T. `motion` is the size of the step.
double icp_step(const Vertices& P, const Matcher& match, double diagonal, double trim, Similarity& T, double& motion,
                std::vector<int>& hints, const JobControl* control, bool hold_scale) {
  const Eigen::Index n = P.rows();
  std::vector<Eigen::Vector3d> x(static_cast<std::size_t>(n));
  std::vector<Match> m(static_cast<std::size_t>(n));
  std::vector<double> d2(static_cast<std::size_t>(n));
  parallel_for(n, threads_of(control), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      if ((i - begin) % 256 == 0) poll(control);  // a query can be slow on a degenerate suspect
      x[i] = T.apply(Eigen::Vector3d(P.row(i).transpose()));
      m[i] = match(x[i], hints[i]);
      hints[i] = m[i].id;
      d2[i] = m[i].distance_squared;
    }
  });
  std::vector<double> sorted = d2;
  const auto keep = std::max<std::size_t>(7, static_cast<std::size_t>(trim * static_cast<double>(n)));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(keep - 1), sorted.end());
  const double cutoff = sorted[keep - 1];

  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  std::size_t kept = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (d2[i] <= cutoff) c += x[i], ++kept;
  c /= static_cast<double>(kept);
  const double unit = diagonal;  // lever arms in units of the diagonal, for conditioning
  Eigen::Matrix<double, 7, 7> A = Eigen::Matrix<double, 7, 7>::Zero();
  Eigen::Matrix<double, 7, 1> b = Eigen::Matrix<double, 7, 1>::Zero();
  double sum = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (d2[i] > cutoff) continue;
    const Eigen::Vector3d& normal = m[i].normal;
    const Eigen::Vector3d r = (x[i] - c) / unit;
    const double residual = (m[i].point - x[i]).dot(normal);
    Eigen::Matrix<double, 7, 1> row;
    // The residual is measured in the suspect's units (divided by the step's growth g, whose
    // derivative adds −ρ at g = 1): in the original's, shrinking the suspect shrinks its noise
    // too, and a noisy copy of a thin, tapered part (a blade) slid and shrank 4 % to fit better.
    row << r.cross(normal), r.dot(normal) + residual / unit, normal / unit;
    A += row * row.transpose();
    b += row * (residual / unit);
    sum += residual * residual;
  }
  if (hold_scale) {  // the scale's row and column decoupled: its step is 0, the others' exact
    A.row(3).setZero();
    A.col(3).setZero();
    A(3, 3) = 1;
    b[3] = 0;
  }
  const Eigen::Matrix<double, 7, 1> theta = A.ldlt().solve(b);
  const Eigen::Matrix3d Rw = rodrigues(theta.head<3>());
  const double grow = 1.0 + theta[3];
  const Eigen::Vector3d tau = theta.tail<3>();
  // New map: x ↦ c + grow·Rw (T(x) − c) + tau.
  T.R = Rw * T.R;
  T.scale *= grow;
  T.t = c + grow * (Rw * (T.t - c)) + tau;
  motion = theta.norm();
  return std::sqrt(sum / static_cast<double>(kept));
}

}  // namespace

Matcher nearest_sample(const RegistrationTarget& target) {
  return [&target](const Eigen::Vector3d& x, int hint) {
    const auto [i, d2] = target.index->nearest(x, hint);
    return Match{target.samples.row(i).transpose(), target.sample_normals.row(i).transpose(), d2, i};
  };
}

Matcher closest_surface_point(const RegistrationTarget& target) {
  return [&target](const Eigen::Vector3d& x, int hint) {
    const TriangleHit hit = *target.tree.closest_point(x, std::numeric_limits<double>::infinity(), hint);
    return Match{hit.point, target.face_normals.row(hit.face).transpose(), hit.distance_squared, hit.face};
  };
}

double run_icp(const Vertices& P, const Matcher& match, double diagonal, int iterations, double trim, double tolerance,
               Similarity& T, int& used, const JobControl* control, bool hold_scale) {
  double rms = std::numeric_limits<double>::infinity();
  const double start_scale = T.scale;
  std::vector<int> hints(static_cast<std::size_t>(P.rows()), -1);
  for (used = 0; used < iterations; ++used) {
    double motion = 0;
    rms = icp_step(P, match, diagonal, trim, T, motion, hints, control, hold_scale);
    // Shrinking the suspect onto a patch of the original (or blowing it up) fits ever better and
    // is no pose: such a fit stops at once.
    const bool collapsing = !(std::abs(std::log(T.scale / start_scale)) < std::log(kMaxScaleChange));
    if (!std::isfinite(rms) || motion < tolerance || collapsing) {
      ++used;
      break;
    }
  }
  return rms;
}

double score(const Vertices& P, const RegistrationTarget& target, double trim, const Similarity& T,
             const JobControl* control) {
  std::vector<double> d2(static_cast<std::size_t>(P.rows()));
  parallel_for(P.rows(), threads_of(control), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      if ((i - begin) % 256 == 0) poll(control);
      d2[i] = target.index->nearest(T.apply(Eigen::Vector3d(P.row(i).transpose()))).second;
    }
  });
  const auto keep = std::max<std::size_t>(1, static_cast<std::size_t>(trim * static_cast<double>(d2.size())));
  std::nth_element(d2.begin(), d2.begin() + static_cast<long>(keep - 1), d2.end());
  double sum = 0;
  for (std::size_t i = 0; i < d2.size(); ++i)
    if (d2[i] <= d2[keep - 1]) sum += d2[i];
  return sum;
}

}  // namespace meshmark::registration
