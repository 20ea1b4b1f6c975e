#include "core/registration/pose_vote.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace meshmark {

namespace {

// Three matches whose triangles have the same shape (side ratios within 5 %), not degenerate:
// worth a pose.
bool congruent(const PointMatch& a, const PointMatch& b, const PointMatch& c) {
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
std::vector<std::size_t> agreeing(const std::vector<PointMatch>& matches, const Similarity& T, double tolerance,
                                  std::vector<char>& used) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    char& taken = used[static_cast<std::size_t>(matches[i].original_index)];
    if (!taken && (T.apply(matches[i].suspect) - matches[i].original).norm() <= tolerance) out.push_back(i), taken = 1;
  }
  for (const std::size_t i : out) used[static_cast<std::size_t>(matches[i].original_index)] = 0;
  return out;
}

Similarity fit_agreeing(const std::vector<PointMatch>& matches, const std::vector<std::size_t>& chosen) {
  Eigen::Matrix3Xd from(3, static_cast<Eigen::Index>(chosen.size())), to(3, from.cols());
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    from.col(static_cast<Eigen::Index>(i)) = matches[chosen[i]].suspect;
    to.col(static_cast<Eigen::Index>(i)) = matches[chosen[i]].original;
  }
  return fit_similarity(from, to);
}

namespace {

// How many of the first `prefix` of `live` land within `tolerance` under `T`: a cheap look before
// the full count, which most hypotheses (three matches that are not all right) fail.
std::size_t agreeing_in_prefix(const std::vector<PointMatch>& live, std::size_t prefix, const Similarity& T,
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
std::vector<std::size_t> largest_agreement(const std::vector<PointMatch>& matches, const std::vector<char>& open,
                                           double tolerance, std::size_t original_count, std::size_t min_support,
                                           const PoseVoteOptions& options, const JobControl* control) {
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < matches.size(); ++i)
    if (open[i]) candidates.push_back(i);
  if (candidates.size() < std::max<std::size_t>(3, min_support)) return {};
  std::mt19937 random(20261204);                               // fixed: a detection is reproducible
  std::shuffle(candidates.begin(), candidates.end(), random);  // so that any prefix is a random sample
  std::vector<PointMatch> live;
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
    const PointMatch &a = live[pick(random)], &b = live[pick(random)], &c = live[pick(random)];
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

}  // namespace

std::vector<Similarity> vote_poses(const std::vector<PointMatch>& matches, std::size_t original_count, double tolerance,
                                   const PoseVoteOptions& options, const JobControl* control) {
  const auto needed = std::max<std::size_t>(static_cast<std::size_t>(options.min_agreeing),
                                            static_cast<std::size_t>(options.min_agreeing_share * matches.size()));
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
    std::vector<PointMatch> supporting;
    for (const std::size_t i : best) supporting.push_back(matches[i]), open[i] = 0;
    std::vector<std::size_t> all(supporting.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    const Similarity first = fit_agreeing(supporting, all);
    poses.push_back(fit_agreeing(supporting, agreeing(supporting, first, tolerance, used)));
  }
  return poses;
}

}  // namespace meshmark
