#include "core/registration/align_meshes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "core/util/parallel_for.hpp"

#include "core/mesh/surface_moments.hpp"
#include "core/mesh/vertex_normals.hpp"
#include "core/metrics/compare_meshes.hpp"

namespace meshmark {

namespace {

struct Moments {
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;
  Eigen::Vector3d variances;  // along `axes`, decreasing
  double spread;
};

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

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

// A correspondence: a point on (or near) the original and the normal of the plane there.
struct Match {
  Eigen::Vector3d point, normal;
  double distance_squared;
};
using Matcher = std::function<Match(const Eigen::Vector3d&)>;

// One trimmed point-to-plane step with scale (unless `hold_scale`); returns the RMS of the kept
// plane distances and updates T. `motion` is the size of the step.
double icp_step(const Vertices& P, const Matcher& match, double diagonal, double trim, Similarity& T, double& motion,
                const JobControl* control, bool hold_scale) {
  const Eigen::Index n = P.rows();
  std::vector<Eigen::Vector3d> x(static_cast<std::size_t>(n));
  std::vector<Match> m(static_cast<std::size_t>(n));
  std::vector<double> d2(static_cast<std::size_t>(n));
  parallel_for(n, threads_of(control), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      if ((i - begin) % 256 == 0) poll(control);  // a query can be slow on a degenerate suspect
      x[i] = T.apply(Eigen::Vector3d(P.row(i).transpose()));
      m[i] = match(x[i]);
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
    row << r.cross(normal), r.dot(normal), normal / unit;
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

Matcher nearest_sample(const RegistrationTarget& target) {
  return [&target](const Eigen::Vector3d& x) {
    const auto [i, d2] = target.index->nearest(x);
    return Match{target.samples.row(i).transpose(), target.sample_normals.row(i).transpose(), d2};
  };
}

Matcher closest_surface_point(const RegistrationTarget& target) {
  return [&target](const Eigen::Vector3d& x) {
    const TriangleHit hit = *target.tree.closest_point(x);
    return Match{hit.point, target.face_normals.row(hit.face).transpose(), hit.distance_squared};
  };
}

double run_icp(const Vertices& P, const Matcher& match, double diagonal, int iterations, double trim, double tolerance,
               Similarity& T, int& used, const JobControl* control, bool hold_scale = false) {
  double rms = std::numeric_limits<double>::infinity();
  const double start_scale = T.scale;
  for (used = 0; used < iterations; ++used) {
    double motion = 0;
    rms = icp_step(P, match, diagonal, trim, T, motion, control, hold_scale);
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

// Trimmed RMS distance from the transformed points to the target's samples, without iterating.
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

}  // namespace

RegistrationTarget::RegistrationTarget(Mesh original, const RegistrationSampling& sampling)
    : mesh(std::move(original)), tree(mesh.V, mesh.F), face_normals(meshmark::face_normals(mesh.V, mesh.F)) {
  const auto wanted = static_cast<Eigen::Index>(sampling.samples_per_vertex * static_cast<double>(mesh.V.rows()));
  const auto count =
      static_cast<std::size_t>(std::clamp<Eigen::Index>(wanted, sampling.min_samples, sampling.max_samples));
  std::vector<int> faces;
  samples = sample_surface(mesh, count, &faces);
  sample_normals.resize(samples.rows(), 3);
  for (Eigen::Index i = 0; i < samples.rows(); ++i) sample_normals.row(i) = face_normals.row(faces[i]);
  index = std::make_unique<PointIndex>(samples);
  const Moments m = principal_moments(samples);
  centroid = m.centroid;
  axes = m.axes;
  variances = m.variances;
  spread = m.spread;
  diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
}

namespace {

// The share of `samples` (suspect coordinates) that `a` brings within kOverlapDistance of the
// original's dense samples; none when it shrank the suspect to a speck (under 5 % of the
// original's diagonal), which lies on the surface without being a copy of it.
double overlap(const Alignment& a, const Vertices& samples, const RegistrationTarget& target) {
  const Vertices aligned = a.apply_to_rows(samples);
  if (aligned.rows() == 0) return 0;
  const double extent = (aligned.colwise().maxCoeff() - aligned.colwise().minCoeff()).norm();
  if (extent < 0.05 * target.diagonal) return 0;
  const double reach = kOverlapDistance * target.diagonal;
  Eigen::Index near = 0;
  for (Eigen::Index i = 0; i < aligned.rows(); ++i)
    near += target.index->nearest(aligned.row(i).transpose()).second <= reach * reach;
  return static_cast<double>(near) / static_cast<double>(aligned.rows());
}

// A fit's residual in the suspect's own units (up to one factor common to its fits): poses that
// scale the suspect differently compare fairly, where in the original's units a suspect shrunk
// onto a thin part of the original lies closer than its true pose does.
double suspect_rms(const Alignment& a) {
  return a.transform.scale > 0 ? a.rms / a.transform.scale : std::numeric_limits<double>::infinity();
}

// Sound fits first, then the closest; a collapsed fit last however close (a suspect shrunk onto a
// speck of the original lies on it).
bool fits_better(const Alignment& a, const Alignment& b) {
  if (a.collapsed != b.collapsed) return !a.collapsed;
  return a.poor() != b.poor() ? !a.poor() : suspect_rms(a) < suspect_rms(b);
}

// The suspect's surface samples each stage of a fit uses.
struct SuspectSamples {
  Vertices coarse, dense, polish;
};

// The full fit from a start: ICP on few samples until it settles (a slide along a long, thin
// shape's axis takes a hundred steps), on dense samples, then a polish on exact closest points.
// `hold_scale`: the start's scale is kept until the exact polish (a start at the vertex spacing's).
Alignment refine(const SuspectSamples& samples, const RegistrationTarget& target, const AlignOptions& options,
                 Similarity start, const std::string& name, const JobControl* control, bool hold_scale = false) {
  Alignment a;
  a.transform = start;
  a.start = name;
  int dense = 0;
  run_icp(samples.coarse, nearest_sample(target), target.diagonal, options.max_iterations, options.trim,
          options.tolerance, a.transform, a.iterations, control, hold_scale);
  run_icp(samples.dense, nearest_sample(target), target.diagonal, options.dense_iterations, options.trim,
          options.tolerance, a.transform, dense, control, hold_scale);
  a.iterations += dense;
  // Exact closest points: samples leave a floor of about 1e-5 of the diagonal.
  int polished = 0;
  const double rms = run_icp(samples.polish, closest_surface_point(target), target.diagonal, options.polish_iterations,
                             options.trim, options.tolerance * 1e-3, a.transform, polished, control);
  a.iterations += polished;
  a.rms = rms / target.diagonal;
  a.overlap = overlap(a, samples.polish, target);
  a.collapsed = !(std::abs(std::log(a.transform.scale / start.scale)) < std::log(kMaxScaleChange));
  return a;
}

// Two fits that put the suspect in about the same place: one candidate.
bool same_pose(const Similarity& a, const Similarity& b, double diagonal) {
  const double turn = Eigen::AngleAxisd(a.R * b.R.transpose()).angle();
  return turn < 0.1 && (a.t - b.t).norm() < 0.02 * diagonal && std::abs(std::log(a.scale / b.scale)) < 0.05;
}

// The probed starts worth a full fit, best first: the best, the suspect's own pose (a leak often
// keeps it), and every other distinct pose, all of them fitting about as well as the best (a
// shape with symmetries fits as well turned, and only the watermark tells which turn is the
// original's). A fit whose scale ran far from its start's (ICP shrinking the suspect onto a
// point of the original, or blowing it up) is no candidate.
std::vector<std::size_t> distinct_fits(const std::vector<Similarity>& starts, const std::vector<Similarity>& fits,
                                       const std::vector<double>& rms, double diagonal, const AlignOptions& options) {
  std::vector<std::size_t> order;
  for (std::size_t s = 0; s < fits.size(); ++s)
    if (std::isfinite(rms[s]) && std::abs(std::log(fits[s].scale / starts[s].scale)) < std::log(kMaxScaleChange))
      order.push_back(s);
  if (order.empty()) return {0};
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rms[a] < rms[b]; });
  std::stable_partition(order.begin() + 1, order.end(), [](std::size_t s) { return s == 0; });  // identity next
  std::vector<std::size_t> chosen{order.front()};
  for (std::size_t k = 1; k < order.size() && static_cast<int>(chosen.size()) < kMaxAlignmentCandidates; ++k) {
    const std::size_t s = order[k];
    if (!(rms[s] <= options.candidate_margin * rms[order.front()])) continue;
    if (std::none_of(chosen.begin(), chosen.end(),
                     [&](std::size_t c) { return same_pose(fits[s], fits[c], diagonal); }))
      chosen.push_back(s);
  }
  return chosen;
}

// Turns about the original's centroid that its principal axes cannot tell apart: about an axis
// whose two companions have about the same variance (a bottle, a wheel), or any turn when all
// three have (a ball). Empty when the axes are distinct.
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

// Turns by 30° steps about each of the original's principal axes: where a part of the shape that
// its axes do not see (a rock under a round tower) fixes the turn, and the axes of a cut copy
// moved with the cut.
// The axis-ordered starts include each one turned by 180° about every axis: turns up to 150° reach
// every other 30° step.
std::vector<Eigen::Matrix3d> turns_about_axes(const Eigen::Matrix3d& axes) {
  std::vector<Eigen::Matrix3d> turns;
  for (int axis = 0; axis < 3; ++axis)
    for (int k = 1; k < 6; ++k) turns.push_back(Eigen::AngleAxisd(k * M_PI / 6, axes.col(axis)).toRotationMatrix());
  return turns;
}

// The spacing's starts (spacing_starts) refined briefly, the best ranked of them.
constexpr std::size_t kProbedSpacedStarts = 4;

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

// The median over vertices of the shortest edge each has: a copy that kept the original's
// vertices, however cut, keeps their spacing, so the ratio of two spacings is its scale where the
// spread of a cut copy is not. 0 for a mesh without edges.
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

// The scale that matches the suspect's vertex spacing to the original's; 0 when either has none.
double spacing_scale(const Mesh& suspect, const RegistrationTarget& target) {
  const double suspect_spacing = vertex_spacing(suspect), original_spacing = vertex_spacing(target.mesh);
  return suspect_spacing > 0 ? original_spacing / suspect_spacing : 0;
}

// The starts: the identity, the 24 rotations mapping the suspect's principal axes onto the
// original's, and those turned by every ambiguous_turns (and, for a search again, by
// turns_about_axes too).
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
    for (const Eigen::Matrix3d& turn : turns_about_axes(target.axes)) turns.push_back(turn);
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

// The four axis-ordered starts of starting_poses (after the identity) at the scale of the vertex
// spacing, each about the centroids and at either end (rescaled); none when the spacing says
// nothing.
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

}  // namespace

bool turns_ambiguous(const RegistrationTarget& target) {
  return !ambiguous_turns(target.variances, target.axes).empty();
}

const ShapeFeatures& RegistrationTarget::shape_features(const FeatureOptions& options, int threads) const {
  std::call_once(described_, [&] {
    features_ = std::make_unique<ShapeFeatures>(mesh, options.original_points, options.neighbours, threads);
  });
  return *features_;
}

const VertexSignatures& RegistrationTarget::vertex_signatures(int threads) const {
  std::call_once(signed_, [&] { signatures_ = std::make_unique<VertexSignatures>(mesh.V, threads); });
  return *signatures_;
}

namespace {

const Eigen::Matrix3d kReflection = Eigen::Vector3d(-1, 1, 1).asDiagonal();

// The similarity taking `suspect`'s vertices onto the original's in their order, when nearly all
// land within the vertex matching's tolerance, refitted on those that do. None otherwise.
std::optional<Similarity> pose_by_order(const Vertices& suspect, const Vertices& original, double tolerance) {
  Similarity pose = fit_similarity(suspect.transpose(), original.transpose());
  const Eigen::ArrayXd misses = (pose.apply_to_rows(suspect) - original).rowwise().norm().array();
  const Eigen::Index landed = (misses <= tolerance).count();
  if (static_cast<double>(landed) < kOrderKeptShare * static_cast<double>(original.rows())) return std::nullopt;
  Eigen::Matrix3Xd from(3, landed), to(3, landed);
  for (Eigen::Index i = 0, k = 0; i < original.rows(); ++i)
    if (misses[i] <= tolerance) from.col(k) = suspect.row(i).transpose(), to.col(k++) = original.row(i).transpose();
  return fit_similarity(from, to);
}

// A copy that kept the original's vertices in their order (the file as handed out, moved or not,
// or mirrored) names its pose by them (pose_by_order), polished. None otherwise (a reordered,
// simplified or remeshed copy).
std::vector<Alignment> align_by_order(const Mesh& suspect, const RegistrationTarget& target,
                                      const AlignOptions& options, const JobControl* control) {
  const Vertices& original = target.mesh.V;
  if (suspect.V.rows() != original.rows() || original.rows() < 4) return {};
  const double tolerance = VertexMatchOptions{}.tolerance * target.diagonal;
  std::optional<Similarity> pose = pose_by_order(suspect.V, original, tolerance);
  const bool mirrored = !pose && options.try_mirror;
  if (mirrored) {
    pose = pose_by_order(suspect.V * kReflection, original, tolerance);
    if (pose) pose->R = pose->R * kReflection;
  }
  if (!pose) return {};
  const Vertices polish = sample_surface(suspect, static_cast<std::size_t>(options.polish_points));
  AlignOptions exact = options;  // the pose is the vertices' own: only the polish on closest points
  exact.max_iterations = exact.dense_iterations = 0;
  Alignment a = refine({polish, polish, polish}, target, exact, *pose, "order", control);
  a.mirrored = mirrored;
  return {a};
}

// The poses the vertices a suspect kept imply, each refined as any start is; none when too few
// kept.
std::vector<Alignment> align_by_vertices(const Mesh& suspect, const RegistrationTarget& target,
                                         const AlignOptions& options, const JobControl* control) {
  VertexMatchOptions matching;
  matching.vote.max_poses = kMaxAlignmentCandidates;
  const VertexPoses found =
      match_vertices(suspect, target.vertex_signatures(threads_of(control)), target.diagonal, matching, control);
  if (found.poses.empty()) return {};
  const SurfaceSampler sampler(suspect);
  const Vertices polish = sampler.sample(static_cast<std::size_t>(options.polish_points));
  const Vertices points = sampler.sample(static_cast<std::size_t>(options.max_points));
  AlignOptions close = options;  // already close: no coarse steps, which a ball lets slide
  close.max_iterations = 0;
  std::vector<Alignment> out;
  // Poses of the distinctive matches alone have a lower bar: one that fits poorly, unbent too, is
  // searched again by shape (align_candidates), as it is not named "vertices".
  for (const Similarity& pose : found.poses)
    out.push_back(refine({polish, points, polish}, target, close, pose,
                         found.distinctive ? "distinct vertices" : "vertices", control));
  std::stable_sort(out.begin(), out.end(), fits_better);
  return out;
}

// Whether `field` keeps the extent of `points` within a quarter: bending and twisting move a
// shape's parts, a field that flattens it onto a patch of the original fits better still.
bool keeps_size(const SmoothDeformation& field, const Vertices& points) {
  const auto extent = [](const Vertices& P) { return (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm(); };
  const double ratio = extent(field.apply_to_rows(points)) / std::max(extent(points), 1e-300);
  return ratio > 0.8 && ratio < 1.25;
}

// A bent, twisted or posed copy fits no rigid pose well: where a smooth field fits it much
// better (DeformationOptions::min_gain), the pose with the field becomes a candidate beside the
// rigid one, which stays: a field fitted to what is not a bend (a smoothed copy that shrank) can
// take a share of a small mesh's coarse carriers, and the reading keeps the stronger.
void unbend(std::vector<Alignment>& alignments, const Mesh& suspect, const RegistrationTarget& target,
            const AlignOptions& options, const JobControl* control) {
  if (!options.non_rigid) return;
  const Vertices samples = sample_surface(suspect, static_cast<std::size_t>(options.polish_points));
  double best_rigid = std::numeric_limits<double>::infinity();
  for (const Alignment& a : alignments)
    if (!a.collapsed) best_rigid = std::min(best_rigid, a.rms);
  std::vector<Alignment> unbent;
  for (Alignment a : alignments) {
    // No pose to unbend, one the best rigid fit already beats by far, or one already as close as a
    // mark alone leaves it.
    if (a.collapsed || a.rms > options.candidate_margin * best_rigid || a.rms < options.deformation.min_rigid_rms)
      continue;
    const Vertices posed = a.transform.apply_to_rows(samples);
    const DeformationFit fit =
        fit_smooth_deformation(posed, target.tree, target.face_normals, target.diagonal, options.deformation, control);
    if (!fits_much_better(fit, target.diagonal, options.deformation)) continue;
    if (!keeps_size(fit.deformation, posed)) continue;  // a squash, not a bend
    a.deformation = fit.deformation;
    a.rms = fit.deformed_rms / target.diagonal;
    a.overlap = overlap(a, samples, target);
    unbent.push_back(std::move(a));
  }
  alignments.insert(alignments.end(), unbent.begin(), unbent.end());
  std::stable_sort(alignments.begin(), alignments.end(), fits_better);
}

std::vector<Alignment> rigid_candidates(const Mesh& suspect, const RegistrationTarget& target,
                                        const AlignOptions& options, const JobControl* control) {
  // The vertices a copy kept name its pose exactly, whatever was cut away or however it was
  // turned: their poses are the candidates (one, unless the original repeats a part). Only a copy that kept none
  // (remeshed, simplified, noisy) is registered by its shape.
  if (options.try_order)
    if (auto by_order = align_by_order(suspect, target, options, control); !by_order.empty()) return by_order;
  if (options.try_vertices)
    if (auto by_vertices = align_by_vertices(suspect, target, options, control); !by_vertices.empty())
      return by_vertices;
  const SurfaceSampler sampler(suspect);
  const Vertices points = sampler.sample(static_cast<std::size_t>(options.max_points));
  const Vertices probe = sampler.sample(static_cast<std::size_t>(options.probe_points));
  const Vertices scoring = sampler.sample(static_cast<std::size_t>(options.score_points));
  const Moments m = principal_moments(points);

  std::vector<std::pair<Similarity, std::string>> starts = starting_poses(m, target, options.turn_about_every_axis);
  const std::size_t shape_starts = starts.size();
  if (options.try_features) {
    const std::vector<Similarity> voted =
        match_features(suspect, target.spread / m.spread, target.shape_features(options.features, threads_of(control)),
                       options.features, control);
    for (std::size_t k = 0; k < voted.size(); ++k) starts.emplace_back(voted[k], "features " + std::to_string(k));
  }
  // Rank all starts as they are, refine the best few (and the identity) briefly.
  std::vector<std::pair<double, std::size_t>> ranked;
  for (std::size_t s = 0; s < starts.size(); ++s)
    ranked.emplace_back(score(scoring, target, options.trim, starts[s].first, control), s);
  std::sort(ranked.begin(), ranked.end());
  // The spacing's starts rank among themselves: a simplified copy's spacing shrinks it, and a
  // speck lies closer to any surface than the right pose of the whole copy does (the arm cut and
  // simplified: every probe went to them, a twelfth of its scale).
  // They keep their scale while ICP finds their place (probe, coarse and dense fits): a half blade
  // fits better shrunk and slid toward its tip, where ICP with its scale free drifted from the
  // start (the sword cut by half: 6.5 % small, a quarter of the bits wrong).
  const std::size_t spaced_from = starts.size();
  if (options.try_spacing)
    for (auto& start : spacing_starts(starts, m, points, spacing_scale(suspect, target), target))
      starts.push_back(std::move(start));
  std::vector<std::pair<double, std::size_t>> spaced_ranked;
  for (std::size_t s = spaced_from; s < starts.size(); ++s)
    spaced_ranked.emplace_back(score(scoring, target, options.trim, starts[s].first, control), s);
  std::sort(spaced_ranked.begin(), spaced_ranked.end());
  std::vector<Similarity> refined(starts.size());
  std::vector<double> probe_rms(starts.size(), std::numeric_limits<double>::infinity());
  const auto probe_from = [&](std::size_t s) {
    refined[s] = starts[s].first;
    int used = 0;
    const double rms = run_icp(probe, nearest_sample(target), target.diagonal, options.probe_iterations, options.trim,
                               options.tolerance, refined[s], used, control, s >= spaced_from);
    // In the suspect's own units: a wrong start that shrank onto a limb lies close to the
    // original in its units only (the mite cut and simplified: a third of its scale, ranked first).
    probe_rms[s] = rms / refined[s].scale;
  };
  // More starts than the 25 of the axes: turns the axes cannot tell apart, each worth a look.
  const int probed = shape_starts > 25 ? options.probed_turned_starts : options.probed_starts;
  for (int r = 0; r < std::min<int>(probed, static_cast<int>(ranked.size())); ++r) probe_from(ranked[r].second);
  for (std::size_t s = shape_starts; s < spaced_from; ++s)  // few, and voted for by the shape
    if (!std::isfinite(probe_rms[s])) probe_from(s);
  for (std::size_t r = 0; r < std::min<std::size_t>(kProbedSpacedStarts, spaced_ranked.size()); ++r)
    probe_from(spaced_ranked[r].second);
  if (!std::isfinite(probe_rms[0])) probe_from(0);
  const Vertices polish = sampler.sample(static_cast<std::size_t>(options.polish_points));
  const SuspectSamples samples{polish, points, polish};
  std::vector<Alignment> out;
  std::vector<Similarity> start_poses;
  for (const auto& start : starts) start_poses.push_back(start.first);
  for (const std::size_t s : distinct_fits(start_poses, refined, probe_rms, target.diagonal, options))
    out.push_back(refine(samples, target, options, refined[s], starts[s].second, control, s >= spaced_from));
  std::stable_sort(out.begin(), out.end(), fits_better);
  return out;
}

}  // namespace

bool Alignment::poor() const { return rms > kPoorAlignmentRms || overlap < kPoorOverlap || collapsed; }

namespace {

// Rigid candidates, each beside its unbent twin where a smooth field fits much better.
std::vector<Alignment> fit_poses(const Mesh& suspect, const RegistrationTarget& target, const AlignOptions& options,
                                 const JobControl* control) {
  std::vector<Alignment> alignments = rigid_candidates(suspect, target, options, control);
  for (Alignment& a : alignments) a.rigid_rms = a.rms;
  unbend(alignments, suspect, target, options, control);
  return alignments;
}

// The suspect reflected through the plane x = 0, its faces rewound so that they face as before.
Mesh mirror_image(const Mesh& suspect) {
  Mesh mirrored{suspect.V * kReflection, suspect.F};
  mirrored.F.col(1).swap(mirrored.F.col(2));
  return mirrored;
}

// Poses of the suspect's mirror image as poses of the suspect itself.
std::vector<Alignment> reflected(std::vector<Alignment> alignments) {
  for (Alignment& a : alignments) {
    a.transform.R = a.transform.R * kReflection;
    a.mirrored = true;
  }
  return alignments;
}

std::vector<Alignment> fit_mirrored_poses(const Mesh& suspect, const RegistrationTarget& target,
                                          const AlignOptions& options, const JobControl* control) {
  return reflected(fit_poses(mirror_image(suspect), target, options, control));
}

bool by_kept_vertices(const Alignment& a) { return a.start == "vertices" || a.start == "order"; }

// A poor best fit, or one that leaves part of the suspect off the original, may have missed the
// basin of a start ranked low or of a turn the axes do not name: every start, and each turned
// about every axis, is probed again, and the better of the two searches kept. So may a poor rigid
// pose that a smooth field made look good (a wrong turn of a closed hand, bent onto the
// original): a bent copy pays for a second search.
bool worth_searching_again(const Alignment& best) {
  return (best.poor() || best.rigid_rms > kPoorAlignmentRms || best.overlap < kWholeOverlap) && !by_kept_vertices(best);
}

std::vector<Alignment> searched_again_if_poor(std::vector<Alignment> alignments, const Mesh& suspect,
                                              const RegistrationTarget& target, const AlignOptions& options,
                                              const JobControl* control) {
  if (!options.retry_poor || !worth_searching_again(alignments.front())) return alignments;
  AlignOptions wider = options;
  wider.probed_starts = wider.probed_turned_starts = std::numeric_limits<int>::max() / 2;
  wider.turn_about_every_axis = true;
  // Kept vertices, their spacing and local shape gave the same starts the first time.
  wider.retry_poor = wider.try_vertices = wider.try_order = wider.try_features = wider.try_spacing = false;
  std::vector<Alignment> again = fit_poses(suspect, target, wider, control);
  return fits_better(again.front(), alignments.front()) ? again : alignments;
}

// A mirrored copy fits far better reflected: its poses alone. A shape alike to its mirror image
// fits about as well either way, and only the mark tells which is the copy's: the reflected poses
// that fit within the margin join the candidates, after the suspect's own (most copies are not
// mirrored, and a tie is the shape's, not the mark's). Otherwise the suspect's own poses stand.
bool reflection_wins(const Alignment& own, const Alignment& mirrored, const AlignOptions& options) {
  return fits_better(mirrored, own) &&
         (own.poor() != mirrored.poor() || suspect_rms(own) > options.candidate_margin * suspect_rms(mirrored));
}

std::vector<Alignment> with_mirrored(std::vector<Alignment> own, std::vector<Alignment> mirrored,
                                     const AlignOptions& options) {
  const Alignment& a = own.front();
  if (reflection_wins(a, mirrored.front(), options)) return mirrored;
  for (Alignment& r : mirrored)
    if (!r.collapsed && !r.poor() && suspect_rms(r) <= options.candidate_margin * suspect_rms(a)) own.push_back(r);
  return own;
}

// The closest of the suspect's starts (starting_poses) scored as they are, without a step of ICP.
double best_start_score(const Vertices& points, const RegistrationTarget& target, const AlignOptions& options,
                        const JobControl* control) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& start : starting_poses(principal_moments(points), target, false))
    best = std::min(best, score(points, target, options.trim, start.first, control));
  return best;
}

// How much closer the suspect's mirror image lies to the original than the suspect, by their
// principal-axis starts scored as they are (a few thousand closest points): above 1 the mirror
// image is closer. A copy that is not mirrored fits its reflection far worse unless the shape is
// alike to its mirror image (then about 1: both are searched, and the mark tells).
double mirror_gain(const Mesh& suspect, const RegistrationTarget& target, const AlignOptions& options,
                   const JobControl* control) {
  const Vertices points = sample_surface(suspect, static_cast<std::size_t>(options.score_points));
  return best_start_score(points, target, options, control) /
         best_start_score(points * kReflection, target, options, control);
}

// The suspect's shape searched on both sides of the mirror where the brief look (mirror_gain)
// says its reflection may fit about as well or better; a poor fit is searched again on its own
// side (searched_again_if_poor), unless its reflection is closer by that look, fits well and fits
// far better: a mirrored copy need not pay for the long search of every turn first (the
// armadillo mirrored and renumbered: 6.5 s → 1 s). A shape alike to its mirror image (a tower on
// a rock, cut: its look is about 1) keeps that search: its reflection may fit well at a wrong turn.
std::vector<Alignment> search_both_sides(std::vector<Alignment> own, const Mesh& suspect,
                                         const RegistrationTarget& target, const AlignOptions& options,
                                         const JobControl* control) {
  const double gain = mirror_gain(suspect, target, options, control);
  if (gain < 1 / options.candidate_margin)
    return searched_again_if_poor(std::move(own), suspect, target, options, control);
  std::vector<Alignment> mirrored = fit_mirrored_poses(suspect, target, options, control);
  const bool clearly_mirrored =
      gain > 1 && reflection_wins(own.front(), mirrored.front(), options) && !worth_searching_again(mirrored.front());
  if (!clearly_mirrored) own = searched_again_if_poor(std::move(own), suspect, target, options, control);
  return with_mirrored(std::move(own), std::move(mirrored), options);
}

// The suspect's own poses, and its mirror image's where they may fit about as well or better. A
// copy in the original's vertex order is not mirrored (its order fits one way only; align_by_order
// tries it reflected). Kept vertices fit a mirrored copy of a shape modelled symmetric (a
// character built with a mirror modifier) as exactly turned as reflected: its mirror image's kept
// vertices are registered too, and the mark tells. Any other copy: search_both_sides.
std::vector<Alignment> with_mirror_image(std::vector<Alignment> own, const Mesh& suspect,
                                         const RegistrationTarget& target, const AlignOptions& options,
                                         const JobControl* control) {
  const Alignment& best = own.front();
  if (best.by_order() && !best.poor()) return own;
  if (best.start.ends_with("vertices") && !best.poor()) {
    std::vector<Alignment> mirrored = reflected(align_by_vertices(mirror_image(suspect), target, options, control));
    if (!mirrored.empty() && reflection_wins(best, mirrored.front(), options) &&
        !worth_searching_again(mirrored.front()))
      return mirrored;
    // A pose of the distinctive vertices alone that leaves part of the copy off is searched again.
    own = searched_again_if_poor(std::move(own), suspect, target, options, control);
    return mirrored.empty() ? own : with_mirrored(std::move(own), std::move(mirrored), options);
  }
  return search_both_sides(std::move(own), suspect, target, options, control);
}

}  // namespace

Mesh as_registered(const Mesh& suspect, const Alignment& a) { return a.mirrored ? mirror_image(suspect) : suspect; }

std::vector<Alignment> align_candidates(const Mesh& suspect, const RegistrationTarget& target,
                                        const AlignOptions& options, const JobControl* control) {
  std::vector<Alignment> own = fit_poses(suspect, target, options, control);
  if (!options.try_mirror) return searched_again_if_poor(std::move(own), suspect, target, options, control);
  return with_mirror_image(std::move(own), suspect, target, options, control);
}

Alignment align_to_original(const Mesh& suspect, const RegistrationTarget& target, const AlignOptions& options,
                            const JobControl* control) {
  return align_candidates(suspect, target, options, control).front();
}

}  // namespace meshmark
