#pragma once
// The cotangent Laplacian as a positive semi-definite stiffness matrix.

#include <Eigen/SparseCore>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct CotmatrixOptions {
  /// Edge weights ½(cot α + cot β) below this are raised to it. Negative weights (obtuse
  /// triangles on scanned meshes) break the maximum principle the flow relies on; 0 clamps them.
  double min_weight = 0.0;
  /// Weights above this are lowered to it (needle triangles would otherwise dominate).
  double max_weight = 1e5;
};

/// #V×#V symmetric L with L(i,j) = −w_ij for each edge and L(i,i) = Σ_j w_ij, so xᵀLx ≥ 0.
Eigen::SparseMatrix<double> cotmatrix(const Vertices& V, const Faces& F, const CotmatrixOptions& options = {});

}  // namespace meshmark
