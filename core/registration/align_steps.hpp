#pragma once
// The steps align_candidates composes that the mirror image's registration (align_mirrored.hpp)
// also takes. Internal to core/registration; defined in align_meshes.cpp.

#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/registration/align_meshes.hpp"

namespace meshmark::registration {

/// A fit's residual in the suspect's own units (up to one factor common to its fits): poses that
/// scale the suspect differently compare fairly, where in the original's units a suspect shrunk
/// onto a thin part of the original lies closer than its true pose does.
double suspect_rms(const Alignment& a);

/// Sound fits first, then the closest; a collapsed fit last however close (a suspect shrunk onto a
/// speck of the original lies on it).
bool fits_better(const Alignment& a, const Alignment& b);

/// The poses the vertices a suspect kept imply, each refined as any start is; none when too few
/// kept.
std::vector<Alignment> align_by_vertices(const Mesh& suspect, const RegistrationTarget& target,
                                         const AlignOptions& options, const JobControl* control);

/// Rigid candidates (by order, by kept vertices, or by shape), each beside its unbent twin where a
/// smooth field fits much better.
std::vector<Alignment> fit_poses(const Mesh& suspect, const RegistrationTarget& target, const AlignOptions& options,
                                 const JobControl* control);

/// A poor best fit, or one that leaves part of the suspect off the original, may have missed the
/// basin of a start ranked low or of a turn the axes do not name: every start, and each turned
/// about every axis, is probed again, and the better of the two searches kept. So may a poor rigid
/// pose that a smooth field made look good (a wrong turn of a closed hand, bent onto the
/// original): a bent copy pays for a second search.
bool worth_searching_again(const Alignment& best);

/// The alignments, or those of that search again where worth_searching_again and it fits better.
std::vector<Alignment> searched_again_if_poor(std::vector<Alignment> alignments, const Mesh& suspect,
                                              const RegistrationTarget& target, const AlignOptions& options,
                                              const JobControl* control);

}  // namespace meshmark::registration
