#pragma once
// Smooth non-rigid deformations, as posing a character, warping a print or re-rigging a copy in
// another tool does: both act along the surface's longest principal axis, through its centroid,
// and keep every length along that axis.
//
// twist: each point turns about the axis by an angle growing linearly along it, `degrees` from
//        one end of the shape to the other.
// bend:  the axis is rolled onto a circular arc of `degrees` (its length kept), towards the
//        second principal axis; each point keeps its offset from the axis, measured along the
//        arc's normal.

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Throws std::invalid_argument when |degrees| exceeds 360 (twist) or 180 (bend).
Mesh twist(const Mesh& mesh, double degrees);
Mesh bend(const Mesh& mesh, double degrees);

}  // namespace meshmark
