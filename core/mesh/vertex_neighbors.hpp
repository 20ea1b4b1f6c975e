#pragma once
// Vertices joined to each vertex by an edge, in compressed rows (ascending within a row).

#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct VertexNeighbors {
  std::vector<int> offsets;    ///< #V+1
  std::vector<int> neighbors;  ///< 2·#E
};

VertexNeighbors vertex_neighbors(const Faces& F, Eigen::Index vertex_count);

}  // namespace meshmark
