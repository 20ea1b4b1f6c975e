#include "core/registration/align_meshes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "core/mesh/vertex_normals.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "core/registration/align_mirrored.hpp"
#include "core/registration/align_steps.hpp"
#include "core/registration/icp.hpp"
#include "core/registration/starting_poses.hpp"

namespace meshmark {

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
  const registration::Moments m = registration::principal_moments(samples);
  centroid = m.centroid;
  axes = m.axes;
  variances = m.variances;
  spread = m.spread;
  diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
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

bool Alignment::poor() const { return rms > kPoorAlignmentRms || overlap < kPoorOverlap || collapsed; }

namespace registration {

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

// The suspect's surface samples each stage of a fit uses.
struct SuspectSamples {
  Vertices coarse, dense, polish;
};

// How long a fit keeps its start's scale.
enum class ScaleHeld {
  never,
  until_polish,  // while ICP finds its place; the exact polish may change it (the vertex spacing's starts)
  throughout,    // the scale is the candidate's (a scale the surface leaves open, swept)
};

// The full fit from a start: ICP on few samples until it settles (a slide along a long, thin
// shape's axis takes a hundred steps), on dense samples, then a polish on exact closest points.
Alignment refine(const SuspectSamples& samples, const RegistrationTarget& target, const AlignOptions& options,
                 const Similarity& start, const std::string& name, const JobControl* control,
                 ScaleHeld held = ScaleHeld::never) {
  const bool hold_scale = held != ScaleHeld::never;
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
  const double rms =
      run_icp(samples.polish, closest_surface_point(target), target.diagonal, options.polish_iterations, options.trim,
              options.tolerance * 1e-3, a.transform, polished, control, held == ScaleHeld::throughout);
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
  for (std::size_t k = 1; k < order.size() && static_cast<int>(chosen.size()) < options.refined_fits; ++k) {
    const std::size_t s = order[k];
    if (!(rms[s] <= options.candidate_margin * rms[order.front()])) continue;
    if (std::none_of(chosen.begin(), chosen.end(),
                     [&](std::size_t c) { return same_pose(fits[s], fits[c], diagonal); }))
      chosen.push_back(s);
  }
  return chosen;
}

// The spacing's starts (spacing_starts) refined briefly, the best ranked of them.
constexpr std::size_t kProbedSpacedStarts = 4;

// The similarity taking `suspect`'s vertices onto the original's in their order, when nearly all
// land within the vertex matching's tolerance, refitted on those that do, with the RMS of every
// vertex's miss. None otherwise.
struct OrderPose {
  Similarity pose;
  double rms = 0;
};

std::optional<OrderPose> pose_by_order(const Vertices& suspect, const Vertices& original, double tolerance) {
  Similarity pose = fit_similarity(suspect.transpose(), original.transpose());
  const Eigen::ArrayXd misses = (pose.apply_to_rows(suspect) - original).rowwise().norm().array();
  const Eigen::Index landed = (misses <= tolerance).count();
  if (static_cast<double>(landed) < kOrderKeptShare * static_cast<double>(original.rows())) return std::nullopt;
  Eigen::Matrix3Xd from(3, landed), to(3, landed);
  for (Eigen::Index i = 0, k = 0; i < original.rows(); ++i)
    if (misses[i] <= tolerance) from.col(k) = suspect.row(i).transpose(), to.col(k++) = original.row(i).transpose();
  pose = fit_similarity(from, to);
  return OrderPose{pose, std::sqrt((pose.apply_to_rows(suspect) - original).rowwise().squaredNorm().mean())};
}

// A copy that kept the original's vertices in their order (the file as handed out, moved or not,
// or mirrored) names its pose by them (pose_by_order), polished. None otherwise (a reordered,
// simplified or remeshed copy). Both sides are fitted: a thin, nearly flat part (a scan's
// fragment) mirrored lands its vertices within the tolerance turned as well as reflected, and
// only the right side lands them at the mark's size; the reflection wins where its vertices land
// at most half as far.
std::vector<Alignment> align_by_order(const Mesh& suspect, const RegistrationTarget& target,
                                      const AlignOptions& options, const JobControl* control) {
  const Vertices& original = target.mesh.V;
  if (suspect.V.rows() != original.rows() || original.rows() < 4) return {};
  const double tolerance = VertexMatchOptions{}.tolerance * target.diagonal;
  const std::optional<OrderPose> own = pose_by_order(suspect.V, original, tolerance);
  const std::optional<OrderPose> reflected =
      options.try_mirror ? pose_by_order(suspect.V * kReflection, original, tolerance) : std::nullopt;
  // Clearly closer: a flat sheet's mark, along its normals, misses by as much reflected through
  // the sheet's plane as not, and only the copy's own side reads it.
  const bool mirrored = reflected && (!own || reflected->rms < 0.5 * own->rms);
  if (!own && !mirrored) return {};
  Similarity pose = mirrored ? reflected->pose : own->pose;
  if (mirrored) pose.R = pose.R * kReflection;
  const Vertices polish = sample_surface(suspect, static_cast<std::size_t>(options.polish_points));
  AlignOptions exact = options;  // the pose is the vertices' own: only the polish on closest points
  exact.max_iterations = exact.dense_iterations = 0;
  Alignment a = refine({polish, polish, polish}, target, exact, pose, "order", control);
  a.mirrored = mirrored;
  return {a};
}

}  // namespace

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

namespace {

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

// Steps a probed fit settles further when more fits are probed than refined.
constexpr int kSettleIterations = 40;

// The probed fits `chosen` (indices into `refined`, whose poses they update) each settled on the
// probe samples, the best kMaxAlignmentCandidates of them by their residual in the suspect's
// units: after a brief probe the right turn of a near-symmetric shape ranks among many about as
// close (tower_holes cut, simplified and noisy: fourth of 14 with one seed, seventh with another).
std::vector<std::size_t> settled_best(const std::vector<std::size_t>& chosen, const Vertices& probe,
                                      const RegistrationTarget& target, const AlignOptions& options,
                                      std::vector<Similarity>& refined, std::size_t spaced_from,
                                      const JobControl* control) {
  std::vector<std::pair<double, std::size_t>> settled;
  for (const std::size_t s : chosen) {
    int used = 0;
    const double probed_scale = refined[s].scale;
    const double rms = run_icp(probe, nearest_sample(target), target.diagonal, kSettleIterations, options.trim,
                               options.tolerance, refined[s], used, control, s >= spaced_from);
    const bool kept_scale = std::abs(std::log(refined[s].scale / probed_scale)) < std::log(kMaxScaleChange);
    settled.emplace_back(
        std::isfinite(rms) && kept_scale ? rms / refined[s].scale : std::numeric_limits<double>::infinity(), s);
  }
  std::stable_sort(settled.begin(), settled.end());
  std::vector<std::size_t> best;
  for (std::size_t k = 0; k < static_cast<std::size_t>(kMaxAlignmentCandidates); ++k) best.push_back(settled[k].second);
  return best;
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
  std::vector<std::size_t> fits = distinct_fits(start_poses, refined, probe_rms, target.diagonal, options);
  if (fits.size() > static_cast<std::size_t>(kMaxAlignmentCandidates))
    fits = settled_best(fits, probe, target, options, refined, spaced_from, control);
  for (const std::size_t s : fits)
    out.push_back(refine(samples, target, options, refined[s], starts[s].second, control,
                         s >= spaced_from ? ScaleHeld::until_polish : ScaleHeld::never));
  std::stable_sort(out.begin(), out.end(), fits_better);
  return out;
}

bool by_kept_vertices(const Alignment& a) { return a.start == "vertices" || a.start == "order"; }

}  // namespace

double suspect_rms(const Alignment& a) {
  return a.transform.scale > 0 ? a.rms / a.transform.scale : std::numeric_limits<double>::infinity();
}

bool fits_better(const Alignment& a, const Alignment& b) {
  if (a.collapsed != b.collapsed) return !a.collapsed;
  return a.poor() != b.poor() ? !a.poor() : suspect_rms(a) < suspect_rms(b);
}

std::vector<Alignment> fit_poses(const Mesh& suspect, const RegistrationTarget& target, const AlignOptions& options,
                                 const JobControl* control) {
  std::vector<Alignment> alignments = rigid_candidates(suspect, target, options, control);
  for (Alignment& a : alignments) a.rigid_rms = a.rms;
  unbend(alignments, suspect, target, options, control);
  return alignments;
}

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
  wider.refined_fits = 2 * options.refined_fits;  // many more starts, ranked by brief probes
  // Kept vertices, their spacing and local shape gave the same starts the first time.
  wider.retry_poor = wider.try_vertices = wider.try_order = wider.try_features = wider.try_spacing = false;
  std::vector<Alignment> again = fit_poses(suspect, target, wider, control);
  return fits_better(again.front(), alignments.front()) ? again : alignments;
}

namespace {

// Scales a fit is tried at when its own leaves the scale open (with_open_scale_swept): every 1 %
// within 3 %, the reading's tolerance being about half a percent.
constexpr std::array<double, 6> kSweptScales = {0.97, 0.98, 0.99, 1.01, 1.02, 1.03};
// A refit at ±3 % whose residual (in the suspect's units) is within this factor of the fit's: the
// surface does not fix the scale to the reading's tolerance.
constexpr double kOpenScaleResidual = 1.05;
// The coarse steps of a swept refit: its place is near the fit's, and on the sword's half the
// residual after 20 steps is the one after 200 to four digits.
constexpr int kSweptCoarseIterations = 20;

// Scales a fit that leaves part of the suspect off the original is tried at too
// (with_scales_laddered), relative to its own: a blade cut, simplified and noisy fitted 18-23 %
// small and slid toward its tip.
constexpr std::array<double, 4> kLadderScales = {0.8, 0.9, 1.1, 1.25};
// Then ± these around the best rung, in turn: free, ICP stops a few percent short along a taper
// (the sword 2 % small, where the fit held 2 % larger was a twentieth closer).
constexpr std::array<double, 3> kLadderSteps = {0.05, 0.025, 0.0125};
// How a rung of the ladder is named in `start`; a fit found on it has its scale swept without
// asking the surface (with_open_scale_swept): the ladder was climbed because the surface left it open.
constexpr const char* kLaddered = " laddered";
// A fit leaving more than 1 % of the suspect off the original: at the right pose a cut, simplified
// copy with 0.2 % noise overlaps whole.
constexpr double kFullOverlap = 0.99;

// How a scaled refit runs: its coarse steps, and how long it keeps its scale.
struct ScaledRefit {
  int coarse_iterations = kSweptCoarseIterations;
  ScaleHeld held = ScaleHeld::throughout;  // a polish free to change it drifts back toward the fit's
  const char* label = " scaled";           // in `start`, before the factor
};

// `best` refitted from its pose scaled by `factor` about the suspect's centroid; `samples` are
// the registered suspect's (its mirror image's for a mirrored fit).
Alignment refit_scaled(const Alignment& best, double factor, const SuspectSamples& samples,
                       const RegistrationTarget& target, const AlignOptions& options, const JobControl* control,
                       const ScaledRefit& how = {}) {
  Similarity start = best.transform;
  if (best.mirrored) start.R = start.R * kReflection;  // the pose of the suspect's mirror image
  const Eigen::Vector3d centre = start.apply(Eigen::Vector3d(samples.dense.colwise().mean().transpose()));
  start.scale *= factor;
  start.t = centre + factor * (start.t - centre);
  char name[32];
  std::snprintf(name, sizeof name, "%s %.2f", how.label, factor);
  AlignOptions near = options;
  near.max_iterations = how.coarse_iterations;
  Alignment a = refine(samples, target, near, start, best.start + name, control, how.held);
  if (best.mirrored) a.transform.R = a.transform.R * kReflection, a.mirrored = true;
  a.rigid_rms = a.rms;
  return a;
}

// `best` refitted at each of kLadderScales times its scale, held there, and when one fits better
// in the suspect's units, at the kLadderSteps around the best in turn; the best of them, when one
// beats `best`.
std::optional<Alignment> climbed_ladder(const Alignment& best, const Mesh& suspect, const RegistrationTarget& target,
                                        const AlignOptions& options, const JobControl* control) {
  const Mesh registered = as_registered(suspect, best);  // the sampler keeps a reference
  const Vertices polish = SurfaceSampler(registered).sample(static_cast<std::size_t>(options.polish_points));
  const SuspectSamples samples{polish, polish, polish};
  std::optional<Alignment> leader;
  const auto try_rung = [&](const Alignment& from, double factor, int coarse_iterations) {
    Alignment rung = refit_scaled(from, factor, samples, target, options, control,
                                  {coarse_iterations, ScaleHeld::throughout, kLaddered});
    if (fits_better(rung, leader ? *leader : best)) leader = std::move(rung);
  };
  for (const double factor : kLadderScales) try_rung(best, factor, options.max_iterations);  // far: find the place
  if (!leader) return std::nullopt;
  for (const double step : kLadderSteps) {
    const Alignment centre = *leader;
    try_rung(centre, 1 - step, kSweptCoarseIterations);
    try_rung(centre, 1 + step, kSweptCoarseIterations);
  }
  return leader;
}

// Whether a fit is one the scale ladder may improve: by shape, rigid, close, and leaving part of
// the suspect off the original.
bool ladder_worth_climbing(const Alignment& a) {
  return !a.by_order() && !a.start.ends_with("vertices") && !a.poor() && a.deformation.identity() &&
         a.overlap < kFullOverlap;
}

}  // namespace

// A tapered part fits shrunk and slid along its taper almost as well, and ICP does not climb out
// of it: the best fit that leaves part of the suspect off the original is tried at other scales
// (climbed_ladder), and the best of them leads when it fits better (the sword cut, simplified and
// noisy: its true pose fits a quarter closer).
std::vector<Alignment> with_scales_laddered(std::vector<Alignment> alignments, const Mesh& suspect,
                                            const RegistrationTarget& target, const AlignOptions& options,
                                            const JobControl* control) {
  if (!options.sweep_open_scale || !ladder_worth_climbing(alignments.front())) return alignments;
  if (std::optional<Alignment> better = climbed_ladder(alignments.front(), suspect, target, options, control))
    alignments.insert(alignments.begin(), std::move(*better));
  return alignments;
}

// A cut copy of a part alike to itself at another scale (a blade tapering evenly to its tip, cut
// off its hilt) fits shrunk about its tip and slid as well as at its place: the mark's own
// residual is as large as the difference, and a pose 1-2 % small reads noise. Where the best
// rigid fit by shape, refitted 3 % larger and smaller, fits about as well both ways, every 1 %
// between is a candidate, after the others; the reading tells, and its p-value is charged for
// each. A fit by the copy's own vertices is exact, and a bent one is not a scale's question.
std::vector<Alignment> with_open_scale_swept(std::vector<Alignment> alignments, const Mesh& suspect,
                                             const RegistrationTarget& target, const AlignOptions& options,
                                             const JobControl* control) {
  const Alignment best = alignments.front();
  if (!options.sweep_open_scale || best.by_order() || best.start.ends_with("vertices") || best.poor() ||
      !best.deformation.identity())
    return alignments;
  const Mesh registered = as_registered(suspect, best);  // the sampler keeps a reference
  const SurfaceSampler sampler(registered);
  const Vertices polish = sampler.sample(static_cast<std::size_t>(options.polish_points));
  const SuspectSamples samples{polish, polish, polish};  // near the fit's place: no dense stage needed
  std::vector<Alignment> swept;
  const bool laddered = best.start.find(std::string(kLaddered) + " ") != std::string::npos;
  for (const double factor : {kSweptScales.front(), kSweptScales.back()}) {
    swept.push_back(refit_scaled(best, factor, samples, target, options, control));
    if (!laddered && !(suspect_rms(swept.back()) <= kOpenScaleResidual * suspect_rms(best))) return alignments;
  }
  for (std::size_t k = 1; k + 1 < kSweptScales.size(); ++k)
    swept.push_back(refit_scaled(best, kSweptScales[k], samples, target, options, control));
  alignments.insert(alignments.end(), swept.begin(), swept.end());
  return alignments;
}

}  // namespace registration

Mesh as_registered(const Mesh& suspect, const Alignment& a) {
  return a.mirrored ? registration::mirror_image(suspect) : suspect;
}

std::vector<Alignment> align_candidates(const Mesh& suspect, const RegistrationTarget& target,
                                        const AlignOptions& options, const JobControl* control) {
  std::vector<Alignment> own = registration::fit_poses(suspect, target, options, control);
  own = options.try_mirror ? registration::with_mirror_image(std::move(own), suspect, target, options, control)
                           : registration::searched_again_if_poor(std::move(own), suspect, target, options, control);
  own = registration::with_scales_laddered(std::move(own), suspect, target, options, control);
  return registration::with_open_scale_swept(std::move(own), suspect, target, options, control);
}

Alignment align_to_original(const Mesh& suspect, const RegistrationTarget& target, const AlignOptions& options,
                            const JobControl* control) {
  return align_candidates(suspect, target, options, control).front();
}

}  // namespace meshmark
