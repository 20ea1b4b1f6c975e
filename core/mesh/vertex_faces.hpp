#pragma once
// Faces around each vertex, in compressed rows (like libigl's vertex_triangle_adjacency).

#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct VertexFaces {
  std::vector<int> offsets;  ///< #V+1; faces of v are faces[offsets[v] .. offsets[v+1])
  std::vector<int> faces;    ///< 3·#F face indices, ascending within each vertex
};

VertexFaces vertex_faces(const Faces& F, Eigen::Index vertex_count);

}  // namespace meshmark
