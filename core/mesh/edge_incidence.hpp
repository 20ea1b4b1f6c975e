#pragma once
// Undirected edges of a face list and how faces use them, from the raw faces (no repair):
// the ground truth for boundary, non-manifold and orientation checks.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// #E×2 undirected edges, smaller index first.
using Edges = Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>;

struct EdgeIncidence {
  Edges edges;                   ///< #E×2, sorted lexicographically
  std::vector<int> face_count;   ///< #E faces using each edge (1 boundary, 2 manifold, >2 non-manifold)
  std::vector<int> along_count;  ///< #E faces that traverse the edge from edges(e,0) to edges(e,1)
  Faces face_edges;              ///< #F×3 edge of corner k: from F(f,k) to F(f,(k+1)%3)
};

/// An undirected edge as one number: its smaller vertex in the high half, the larger in the low.
inline std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
}

/// Builds the edge list in O(F log F).
EdgeIncidence edge_incidence(const Faces& F);

}  // namespace meshmark
