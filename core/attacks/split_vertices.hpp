#pragma once
// Vertex-splitting attack: what a re-export through another tool does to the vertex list. A
// chosen share of the vertices is stored once per face that uses it, as flat-shaded exports
// and seam splits (one vertex per position and normal or texture coordinate) store them; the
// surface's shape is unchanged, its connectivity is not.

#include <cstdint>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Each vertex is split with probability `fraction` (in [0, 1]), drawn from `seed`.
Mesh split_vertices(const Mesh& mesh, double fraction, std::uint64_t seed);

}  // namespace meshmark
