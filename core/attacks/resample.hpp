#pragma once
// Resampling attack: the surface re-extracted from its signed distance field, as voxel-based
// tools (a remesher, a 3D-print slicer's repair, a volumetric boolean) rebuild it. The distance
// is sampled on a regular grid of the given spacing (exact closest points near the surface, the
// sign from the angle-weighted pseudo-normal of the closest feature; far points take the sign of
// a flood fill from the grid's border; a surface with holes takes every sign from its generalized
// winding number, which closes the holes) and the zero level set is extracted by marching
// tetrahedra (six per cube, no case table: each crossing's triangles are oriented towards the
// outside). Every vertex is new; the result is closed.

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// `spacing` is the grid step as a share of the bounding-box diagonal, in [0.001, 0.1]. Throws
/// std::invalid_argument outside it, or when the grid would exceed 64 million points.
Mesh resample_surface(const Mesh& mesh, double spacing);

}  // namespace meshmark
