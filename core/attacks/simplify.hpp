#pragma once
// Simplification attack: quadric-error edge collapse (Garland and Heckbert 1997) with optimal
// placement of the merged vertex, down to a fraction of the vertices. Collapses that would break
// the manifold (link condition) or fold a face over are skipped, so a closed manifold stays one.

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Keeps round(fraction × #V) vertices (at least 4). Deterministic. Throws std::invalid_argument
/// for a fraction outside (0, 1] or a mesh OpenMesh cannot hold (non-manifold).
Mesh simplify(const Mesh& mesh, double fraction);

}  // namespace meshmark
