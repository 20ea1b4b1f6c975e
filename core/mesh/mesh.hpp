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

/// Whether `a` has `b`'s vertex count and its faces, corner for corner: vertex i of one stands
/// where vertex i of the other does (a marked copy and its original). Eigen's == alone assumes
/// equal sizes.
inline bool same_connectivity(const Mesh& a, const Mesh& b) {
  return a.V.rows() == b.V.rows() && a.F.rows() == b.F.rows() && a.F == b.F;
}

}  // namespace meshmark
