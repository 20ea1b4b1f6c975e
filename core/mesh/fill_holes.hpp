#pragma once
// A surface's holes closed for its spherical map only: each boundary loop gets one new vertex
// near its centroid, fanned to the loop with the surface's winding. The input's vertices and
// faces come first and unchanged; the filling is appended, so everything computed on the filled
// mesh restricts to the original by taking the first rows.

#include <cstddef>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct FilledHoles {
  Mesh mesh;  ///< the original's vertices and faces, then the filling
  Eigen::Index original_vertices = 0;
  Eigen::Index original_faces = 0;
  std::size_t holes = 0;
};

/// For a 2-manifold mesh (every boundary vertex on one boundary loop). Its new vertices lie a
/// little off each loop's mean plane, on the side its filling faces, so no filling face is flat.
FilledHoles fill_holes(const Mesh& mesh);

}  // namespace meshmark
