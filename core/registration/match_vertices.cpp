#include "core/registration/match_vertices.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

// The rows of `points` without repeats (a split or duplicated vertex would be its own neighbour).
Vertices distinct_rows(const Vertices& points) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(points.rows()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<Eigen::Index>(i);
  const auto less = [&](Eigen::Index a, Eigen::Index b) {
    for (int c = 0; c < 3; ++c)
      if (points(a, c) != points(b, c)) return points(a, c) < points(b, c);
    return false;
  };
  std::stable_sort(order.begin(), order.end(), less);  // of repeats, the first is kept
  std::vector<Eigen::Index> kept;
  for (std::size_t i = 0; i < order.size(); ++i)
    if (i == 0 || points.row(order[i]) != points.row(order[i - 1])) kept.push_back(order[i]);
  std::sort(kept.begin(), kept.end());  // the list's own order: samples spread over it evenly
  Vertices out(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = points.row(kept[i]);
  return out;
}

struct VertexPair {
  Eigen::Vector3d suspect, original;
  int original_index;
};

// Three matches whose triangles have the same shape (side ratios within 5 %), not degenerate:
// worth a pose.
bool congruent(const VertexPair& a, const VertexPair& b, const VertexPair& c) {
  const std::array<double, 3> s = {(a.suspect - b.suspect).norm(), (b.suspect - c.suspect).norm(),
                                   (c.suspect - a.suspect).norm()};
  const std::array<double, 3> o = {(a.original - b.original).norm(), (b.original - c.original).norm(),
                                   (c.original - a.original).norm()};
  const double ratio = (o[0] + o[1] + o[2]) / std::max(s[0] + s[1] + s[2], 1e-300);
  double shortest = s[0];
  for (int i = 0; i < 3; ++i) {
    if (std::abs(o[i] - ratio * s[i]) > 0.05 * ratio * s[i]) return false;
    shortest = std::min(shortest, s[i]);
  }
  return shortest > 0.1 * std::max({s[0], s[1], s[2]});
}

// The matches that `T` lands within `tolerance` of their original vertex, one per original vertex:
// many suspect vertices may share the nearest signature, and a pose that piles them onto it
// proves nothing.
std::vector<std::size_t> agreeing(const std::vector<VertexPair>& matches, const Similarity& T, double tolerance,
                                  std::vector<char>& used) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    char& taken = used[static_cast<std::size_t>(matches[i].original_index)];
    if (!taken && (T.apply(matches[i].suspect) - matches[i].original).norm() <= tolerance) out.push_back(i), taken = 1;
  }
  for (const std::size_t i : out) used[static_cast<std::size_t>(matches[i].original_index)] = 0;
  return out;
}

Similarity fit_agreeing(const std::vector<VertexPair>& matches, const std::vector<std::size_t>& chosen) {
  Eigen::Matrix3Xd from(3, static_cast<Eigen::Index>(chosen.size())), to(3, from.cols());
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    from.col(static_cast<Eigen::Index>(i)) = matches[chosen[i]].suspect;
    to.col(static_cast<Eigen::Index>(i)) = matches[chosen[i]].original;
  }
  return fit_similarity(from, to);
}

}  // namespace

namespace {

// The signatures of rows 0, step, 2·step, … of `distinct` (distinct positions), measured among
// all of them: row r of the result is position r·step's.
Eigen::MatrixXd signatures_every(const Vertices& distinct, Eigen::Index step, int threads) {
  const PointIndex index(distinct);
  const Eigen::Index rows = (distinct.rows() + step - 1) / step;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(rows, kSignatureNeighbours);
  parallel_for(rows, threads, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t r = begin; r < end; ++r) {
      const auto near = index.nearest_k(distinct.row(r * step).transpose(), kSignatureNeighbours + 1);  // itself first
      double mean = 0;
      for (std::size_t k = 1; k < near.size(); ++k) mean += std::sqrt(near[k].second);
      mean /= std::max<double>(1, static_cast<double>(near.size() - 1));
      for (std::size_t k = 1; k < near.size() && mean > 0; ++k)
        out(r, static_cast<Eigen::Index>(k - 1)) = std::sqrt(near[k].second) / mean;
    }
  });
  return out;
}

}  // namespace

Eigen::MatrixXd neighbour_signatures(const Vertices& points, Vertices& distinct, int threads) {
  distinct = distinct_rows(points);
  return signatures_every(distinct, 1, threads);
}

VertexSignatures::VertexSignatures(const Vertices& original, int threads)
    : signatures(neighbour_signatures(original, points, threads)), index(std::make_unique<FeatureIndex>(signatures)) {}

namespace {

// How many of the first `prefix` of `live` land within `tolerance` under `T`: a cheap look before
// the full count, which most hypotheses (three matches that are not all right) fail.
std::size_t agreeing_in_prefix(const std::vector<VertexPair>& live, std::size_t prefix, const Similarity& T,
                               double tolerance) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < prefix; ++i) count += (T.apply(live[i].suspect) - live[i].original).norm() <= tolerance;
  return count;
}

// Draws after which three members of a set of `support` among `total` matches would have been
// drawn at once with probability 1 - 1e-4 (RANSAC's usual stopping rule), doubled for the triples
// of such a set that are too thin to try or miss the look at the sample.
double draws_to_find(std::size_t support, std::size_t total) {
  const double share = static_cast<double>(support) / static_cast<double>(std::max<std::size_t>(total, 1));
  const double all_three = std::pow(std::min(share, 1.0), 3);
  if (all_three >= 1) return 1;
  return 2 * std::log(1e-4) / std::log1p(-all_three);
}

// RANSAC over `matches` (only those with `open` set): the largest set agreeing with the pose three
// congruent matches imply, if one of at least `min_support` exists.
std::vector<std::size_t> largest_agreement(const std::vector<VertexPair>& matches, const std::vector<char>& open,
                                           double tolerance, std::size_t original_count, std::size_t min_support,
                                           const VertexMatchOptions& options, const JobControl* control) {
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < matches.size(); ++i)
    if (open[i]) candidates.push_back(i);
  if (candidates.size() < std::max<std::size_t>(3, min_support)) return {};
  std::mt19937 random(20261204);                               // fixed: a detection is reproducible
  std::shuffle(candidates.begin(), candidates.end(), random);  // so that any prefix is a random sample
  std::vector<VertexPair> live;
  for (const std::size_t i : candidates) live.push_back(matches[i]);
  // A pose with the support sought agrees with about that share of any sample; half of it passes.
  const std::size_t prefix = std::min<std::size_t>(live.size(), 256);
  const double sought_share = static_cast<double>(min_support) / static_cast<double>(live.size());
  const auto prefix_needed = static_cast<std::size_t>(0.5 * sought_share * static_cast<double>(prefix));
  std::uniform_int_distribution<std::size_t> pick(0, live.size() - 1);
  std::vector<std::size_t> best;
  std::vector<char> used(original_count, 0);
  double enough_draws = std::min<double>(options.max_trials, draws_to_find(min_support, live.size()));
  for (int trial = 0; trial < enough_draws; ++trial) {
    if (trial % 512 == 0) poll(control);
    const VertexPair &a = live[pick(random)], &b = live[pick(random)], &c = live[pick(random)];
    if (!congruent(a, b, c)) continue;
    Eigen::Matrix3Xd from(3, 3), to(3, 3);
    from << a.suspect, b.suspect, c.suspect;
    to << a.original, b.original, c.original;
    const Similarity pose = fit_similarity(from, to);
    if (agreeing_in_prefix(live, prefix, pose, tolerance) < prefix_needed) continue;
    std::vector<std::size_t> agree = agreeing(live, pose, tolerance, used);
    if (agree.size() <= best.size()) continue;
    best = std::move(agree);
    if (best.size() * 2 > live.size()) break;  // most agree: no better pose to find
    enough_draws = std::min(enough_draws, draws_to_find(std::max(best.size(), min_support), live.size()));
  }
  for (std::size_t& i : best) i = candidates[i];
  return best;
}

}  // namespace

std::vector<Similarity> match_vertices(const Mesh& suspect, const VertexSignatures& original, double diagonal,
                                       const VertexMatchOptions& options, const JobControl* control) {
  const Vertices points = distinct_rows(suspect.V);
  if (points.rows() <= kSignatureNeighbours || original.points.rows() <= kSignatureNeighbours) return {};
  // Each sampled suspect vertex (only those are measured) matched to the original vertex of the
  // nearest signature, and to every other holding the same signature (a part the original repeats).
  const Eigen::Index step = std::max<Eigen::Index>(1, points.rows() / options.max_suspect_points);
  const Eigen::MatrixXd signatures = signatures_every(points, step, threads_of(control));
  std::vector<VertexPair> matches;
  for (Eigen::Index r = 0; r < signatures.rows(); ++r) {
    const Eigen::VectorXd signature = signatures.row(r).transpose();
    const auto near = original.index->nearest_k(signature.data(), 4);
    for (const auto& [j, distance_squared] : near)
      if (distance_squared <= near.front().second * (1 + 1e-9) + 1e-24)
        matches.push_back({points.row(r * step).transpose(), original.points.row(j).transpose(), j});
  }
  const double tolerance = options.tolerance * diagonal;
  const auto needed = std::max<std::size_t>(static_cast<std::size_t>(options.min_agreeing),
                                            static_cast<std::size_t>(options.min_agreeing_share * matches.size()));
  const auto original_count = static_cast<std::size_t>(original.points.rows());
  std::vector<char> open(matches.size(), 1), used(original_count, 0);
  std::vector<Similarity> poses;
  std::size_t first_support = 0;
  // A part repeated in the original (two identical parts, a symmetric model stored twice) lets a
  // copy of one fit each: every pose supported about as well as the first is a candidate.
  while (static_cast<int>(poses.size()) < options.max_poses) {
    const std::size_t min_support = std::max(needed, first_support / 3);
    const std::vector<std::size_t> best =
        largest_agreement(matches, open, tolerance, original_count, min_support, options, control);
    if (best.size() < min_support) break;
    if (poses.empty()) first_support = best.size();
    std::vector<VertexPair> supporting;
    for (const std::size_t i : best) supporting.push_back(matches[i]), open[i] = 0;
    std::vector<std::size_t> all(supporting.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    const Similarity first = fit_agreeing(supporting, all);
    poses.push_back(fit_agreeing(supporting, agreeing(supporting, first, tolerance, used)));
  }
  return poses;
}

}  // namespace meshmark
