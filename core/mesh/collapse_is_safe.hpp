#pragma once
// Whether collapsing a halfedge keeps a triangle mesh a proper 2-manifold. OpenMesh's
// is_collapse_ok() checks the link condition, but lets a tetrahedron collapse into two triangles
// glued along all three edges (a "pillow"), after which further collapses produce faces that
// repeat a vertex. The valence test here forbids that: no interior vertex may end with fewer
// than three neighbours.

#include "core/mesh/openmesh_convert.hpp"

namespace meshmark {

/// True if `h` (from its from-vertex into its to-vertex) may be collapsed. Not const: OpenMesh
/// tags vertices while it checks the link condition.
bool collapse_is_safe(HalfedgeMesh& mesh, HalfedgeMesh::HalfedgeHandle h);

}  // namespace meshmark
