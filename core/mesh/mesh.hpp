#pragma once
// The triangle mesh the whole core works on: plain Eigen matrices, no halfedges.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace meshmark {

/// #V×3 vertex positions, row-major so that one vertex is contiguous in memory.
using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F×3 vertex indices of triangles (counter-clockwise seen from outside when oriented).
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// A triangle soup or mesh: positions and faces, nothing else.
struct Mesh {
  Vertices V;
  Faces F;
};

}  // namespace meshmark
