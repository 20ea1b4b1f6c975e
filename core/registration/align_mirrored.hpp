#pragma once
// Registration of the suspect's mirror image: a copy mirrored by a modelling tool, or by an
// engine of the other handedness, fits no rotation, so its reflection is registered too and its
// poses join or replace the suspect's own. Internal to core/registration.

#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/registration/align_meshes.hpp"

namespace meshmark::registration {

/// The reflection through the plane x = 0.
inline const Eigen::Matrix3d kReflection = Eigen::Vector3d(-1, 1, 1).asDiagonal();

/// The suspect reflected through the plane x = 0, its faces rewound so that they face as before.
Mesh mirror_image(const Mesh& suspect);

/// The suspect's own poses, and its mirror image's where they may fit about as well or better. A
/// copy in the original's vertex order is not mirrored (its order fits one way only; align_by_order
/// tries it reflected). Kept vertices fit a mirrored copy of a shape modelled symmetric (a
/// character built with a mirror modifier) as exactly turned as reflected: its mirror image's kept
/// vertices are registered too, and the mark tells. Any other copy is searched on both sides where
/// a first look says its reflection may fit.
std::vector<Alignment> with_mirror_image(std::vector<Alignment> own, const Mesh& suspect,
                                         const RegistrationTarget& target, const AlignOptions& options,
                                         const JobControl* control);

}  // namespace meshmark::registration
