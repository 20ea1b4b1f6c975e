#include "core/registration/starting_poses.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "core/mesh/surface_moments.hpp"

namespace meshmark::registration {

namespace {

// The 24 rotations D with det(E_o D E_sᵀ) = +1 among signed permutation matrices.
std::vector<Eigen::Matrix3d> signed_permutations() {
  std::vector<Eigen::Matrix3d> out;
  std::array<int, 3> p = {0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
      for (int r = 0; r < 3; ++r) D(r, p[r]) = (signs >> r) & 1 ? -1.0 : 1.0;
      out.push_back(D);
    }
  } while (std::next_permutation(p.begin(), p.end()));
  return out;
}

// The axis whose two companions' variances are the most alike: the shape is nearest to turning
// about it into itself, so its turn is what the axes tell least.
int nearest_symmetry_axis(const Eigen::Vector3d& variances) {
  int best = 0;
  double best_ratio = -1;
  for (int axis = 0; axis < 3; ++axis) {
    const double a = variances[(axis + 1) % 3], b = variances[(axis + 2) % 3];
    const double ratio = std::min(a, b) / std::max({a, b, 1e-300});
    if (ratio > best_ratio) best = axis, best_ratio = ratio;
  }
  return best;
}

// The extent of `points` along `axis`: (min, max) of their projections.
std::pair<double, double> extent_along(const Vertices& points, const Eigen::Vector3d& axis) {
  const Eigen::VectorXd along = points * axis;
  return {along.minCoeff(), along.maxCoeff()};
}

// The start `pca` at another scale, about the centroids and slid along the original's longest
// axis until the copy's low end meets the original's, or its high end: a cut copy keeps one end.
// `target_extent`: the original's extent along that axis.
std::vector<std::pair<Similarity, std::string>> rescaled(const Similarity& pca, const std::string& name, double scale,
                                                         const Moments& m, const Vertices& points,
                                                         const RegistrationTarget& target,
                                                         std::pair<double, double> target_extent) {
  Similarity T = pca;
  T.scale = scale;
  T.t = target.centroid - T.scale * (T.R * m.centroid);
  const Eigen::Vector3d axis = target.axes.col(0);
  const auto [low, high] = extent_along(T.apply_to_rows(points), axis);
  const auto [target_low, target_high] = target_extent;
  Similarity at_low = T, at_high = T;
  at_low.t += (target_low - low) * axis;
  at_high.t += (target_high - high) * axis;
  return {{T, name + " spaced"}, {at_low, name + " spaced low end"}, {at_high, name + " spaced high end"}};
}

}  // namespace

Moments principal_moments(const Vertices& P) {
  Moments m;
  m.centroid = P.colwise().mean().transpose();
  const Eigen::MatrixXd centred = P.rowwise() - m.centroid.transpose();
  const Eigen::Matrix3d covariance = centred.transpose() * centred / static_cast<double>(P.rows());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  m.axes = eigen.eigenvectors().rowwise().reverse();  // decreasing variance
  m.variances = eigen.eigenvalues().reverse();
  m.spread = std::sqrt(std::max(covariance.trace(), 1e-300));
  return m;
}

std::vector<Eigen::Matrix3d> ambiguous_turns(const Eigen::Vector3d& variances, const Eigen::Matrix3d& axes) {
  const bool first_pair = variances_alike(variances[0], variances[1]),
             second_pair = variances_alike(variances[1], variances[2]);
  std::vector<Eigen::Matrix3d> turns;
  if (first_pair && second_pair) {
    std::mt19937 rng(12345);  // a fixed, even spread of turns: uniform random unit quaternions
    std::normal_distribution<double> n;
    for (int k = 0; k < 96; ++k)
      turns.push_back(Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix());
  } else if (first_pair || second_pair) {
    const Eigen::Vector3d about = axes.col(first_pair ? 2 : 0);
    for (int k = 1; k < 24; ++k) turns.push_back(Eigen::AngleAxisd(k * M_PI / 12, about).toRotationMatrix());
  }
  return turns;
}

std::vector<Eigen::Matrix3d> turns_about_axes(const Eigen::Vector3d& variances, const Eigen::Matrix3d& axes) {
  const int finer = nearest_symmetry_axis(variances);
  std::vector<Eigen::Matrix3d> turns;
  for (int axis = 0; axis < 3; ++axis) {
    const int steps = axis == finer ? 12 : 6;
    for (int k = 1; k < steps; ++k)
      turns.push_back(Eigen::AngleAxisd(k * M_PI / steps, axes.col(axis)).toRotationMatrix());
  }
  return turns;
}

double vertex_spacing(const Mesh& mesh) {
  std::vector<double> shortest(static_cast<std::size_t>(mesh.V.rows()), std::numeric_limits<double>::infinity());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      const double length = (mesh.V.row(a) - mesh.V.row(b)).norm();
      if (!(length > 0)) continue;  // a split vertex's twin is no neighbour
      shortest[static_cast<std::size_t>(a)] = std::min(shortest[static_cast<std::size_t>(a)], length);
      shortest[static_cast<std::size_t>(b)] = std::min(shortest[static_cast<std::size_t>(b)], length);
    }
  std::erase_if(shortest, [](double length) { return !std::isfinite(length); });
  if (shortest.empty()) return 0;
  const auto middle = shortest.begin() + static_cast<long>(shortest.size() / 2);
  std::nth_element(shortest.begin(), middle, shortest.end());
  return *middle;
}

double spacing_scale(const Mesh& suspect, const RegistrationTarget& target) {
  const double suspect_spacing = vertex_spacing(suspect), original_spacing = vertex_spacing(target.mesh);
  return suspect_spacing > 0 ? original_spacing / suspect_spacing : 0;
}

std::vector<std::pair<Similarity, std::string>> starting_poses(const Moments& m, const RegistrationTarget& target,
                                                               bool turn_about_every_axis) {
  std::vector<std::pair<Similarity, std::string>> starts;
  starts.emplace_back(Similarity{}, "identity");
  const auto rotations = signed_permutations();
  for (std::size_t k = 0; k < rotations.size(); ++k) {
    Similarity T;
    T.R = target.axes * rotations[k] * m.axes.transpose();
    if (T.R.determinant() < 0) continue;  // a reflection: not a candidate
    T.scale = target.spread / m.spread;
    T.t = target.centroid - T.scale * (T.R * m.centroid);
    starts.emplace_back(T, "pca " + std::to_string(k));
  }
  std::vector<Eigen::Matrix3d> turns = ambiguous_turns(target.variances, target.axes);
  if (turn_about_every_axis)
    for (const Eigen::Matrix3d& turn : turns_about_axes(target.variances, target.axes)) turns.push_back(turn);
  // The first four PCA starts keep the axes in order (every sign with det +1): turn those.
  const std::size_t ordered = std::min<std::size_t>(4, starts.size() - 1);
  for (std::size_t base = 1; base <= ordered; ++base)
    for (std::size_t q = 0; q < turns.size(); ++q) {
      Similarity T = starts[base].first;
      T.R = turns[q] * T.R;
      T.t = target.centroid + turns[q] * (T.t - target.centroid);
      starts.emplace_back(T, starts[base].second + " turn " + std::to_string(q + 1));
    }
  return starts;
}

std::vector<std::pair<Similarity, std::string>> spacing_starts(
    const std::vector<std::pair<Similarity, std::string>>& shape_starts, const Moments& m, const Vertices& points,
    double scale, const RegistrationTarget& target) {
  std::vector<std::pair<Similarity, std::string>> starts;
  if (!(scale > 0)) return starts;
  const auto target_extent = extent_along(target.samples, target.axes.col(0));
  for (std::size_t base = 1; base <= std::min<std::size_t>(4, shape_starts.size() - 1); ++base)
    for (auto& start :
         rescaled(shape_starts[base].first, shape_starts[base].second, scale, m, points, target, target_extent))
      starts.push_back(std::move(start));
  return starts;
}

}  // namespace meshmark::registration

namespace meshmark {

bool turns_ambiguous(const RegistrationTarget& target) {
  return !registration::ambiguous_turns(target.variances, target.axes).empty();
}

}  // namespace meshmark
