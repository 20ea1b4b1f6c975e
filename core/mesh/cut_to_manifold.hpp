#pragma once
// A mesh cut into manifold pieces the way repair tools do it: faces stay joined across an edge
// only where exactly two faces share it with opposite windings; every vertex whose faces then
// fall into several fans (a pinch, the ends of a non-manifold edge, a winding seam) gets one copy
// per extra fan. Faces that repeat a vertex are dropped. Positions are never changed.
// For the attack tools (a halfedge mesh holds only manifold, consistently wound faces); the
// watermark itself never changes a mesh's connectivity.

#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct ManifoldPieces {
  Mesh mesh;                ///< the input's vertices first (same rows), then the copies
  std::vector<int> origin;  ///< per output vertex: the input vertex it copies
  std::size_t dropped_faces = 0;
};

ManifoldPieces cut_to_manifold(const Mesh& mesh);

}  // namespace meshmark
