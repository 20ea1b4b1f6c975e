#pragma once
// Which way a closed mesh's faces wind, and turning them outward.

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Signed volume enclosed by the faces (positive when they wind counter-clockwise seen from
/// outside). Computed about the vertex centroid to limit cancellation.
double signed_volume(const Vertices& V, const Faces& F);

/// The faces, each reversed if the signed volume is negative; the vertex order is untouched.
Faces orient_outward(const Vertices& V, const Faces& F);

}  // namespace meshmark
