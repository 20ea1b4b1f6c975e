#include "core/registration/match_vertices.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/registration/pose_vote.hpp"
#include "core/spatial/morton_order.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

// A match is distinctive when its signature's squared distance is under this share of the next
// nearest's (a distance ratio of about 0.7).
constexpr double kDistinctiveRatio = 0.5;
constexpr std::size_t kMinDistinctiveMatches = 30;

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

// The signatures of rows 0, step, 2·step, … of `distinct` (distinct positions), measured among
// all of them: row r of the result is position r·step's. Queried in Z-order: at millions of
// vertices, queries in file order waited on memory (each answer is the same in any order).
Eigen::MatrixXd signatures_every(const Vertices& distinct, Eigen::Index step, int threads) {
  const PointIndex index(distinct);
  const Eigen::Index rows = (distinct.rows() + step - 1) / step;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(rows, kSignatureNeighbours);
  const std::vector<std::int64_t> order =
      step == 1 ? morton_order(distinct)
                : morton_order(Vertices(distinct(Eigen::seq(0, (rows - 1) * step, step), Eigen::all)));
  parallel_for(rows, threads, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      const std::int64_t r = order[static_cast<std::size_t>(i)];
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

VertexPoses match_vertices(const Mesh& suspect, const VertexSignatures& original, double diagonal,
                           const VertexMatchOptions& options, const JobControl* control) {
  const Vertices points = distinct_rows(suspect.V);
  if (points.rows() <= kSignatureNeighbours || original.points.rows() <= kSignatureNeighbours) return {};
  // Each sampled suspect vertex (only those are measured) matched to the original vertex of the
  // nearest signature, and to every other holding the same signature (a part the original repeats).
  const Eigen::Index step = std::max<Eigen::Index>(1, points.rows() / options.max_suspect_points);
  const Eigen::MatrixXd signatures = signatures_every(points, step, threads_of(control));
  std::vector<PointMatch> matches, distinctive;
  for (Eigen::Index r = 0; r < signatures.rows(); ++r) {
    const Eigen::VectorXd signature = signatures.row(r).transpose();
    const auto near = original.index->nearest_k(signature.data(), 4);
    for (const auto& [j, distance_squared] : near)
      if (distance_squared <= near.front().second * (1 + 1e-9) + 1e-24)
        matches.push_back({points.row(r * step).transpose(), original.points.row(j).transpose(), j});
    if (near.size() > 1 && near[0].second < kDistinctiveRatio * near[1].second)
      distinctive.push_back(
          {points.row(r * step).transpose(), original.points.row(near[0].first).transpose(), near[0].first});
  }
  const auto vote = [&](const std::vector<PointMatch>& among) {
    return vote_poses(among, static_cast<std::size_t>(original.points.rows()), options.tolerance * diagonal,
                      options.vote, control);
  };
  VertexPoses found{vote(matches), false};
  // Where most of a copy is a regular tessellation (a blade's, a cylinder's), its vertices' nearest
  // signatures are any of many alike and drown the few that are right: the matches whose nearest
  // signature is much nearer than the next (Lowe's ratio test) vote again, alone.
  if (found.poses.empty() && distinctive.size() >= kMinDistinctiveMatches) found = {vote(distinctive), true};
  return found;
}

}  // namespace meshmark
