#include "core/registration/align_mirrored.hpp"

#include <limits>
#include <utility>

#include "core/metrics/compare_meshes.hpp"
#include "core/registration/align_steps.hpp"
#include "core/registration/icp.hpp"
#include "core/registration/starting_poses.hpp"

namespace meshmark::registration {

Mesh mirror_image(const Mesh& suspect) {
  Mesh mirrored{suspect.V * kReflection, suspect.F};
  mirrored.F.col(1).swap(mirrored.F.col(2));
  return mirrored;
}

namespace {

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

}  // namespace

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

}  // namespace meshmark::registration
