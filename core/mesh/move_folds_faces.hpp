#pragma once
// The fold check of edge collapses: would moving vertex v to a new position (its edge partner
// `other` merging into it) turn one of the faces around v over, or nearly so?

#include <Eigen/Core>

#include "core/mesh/openmesh_convert.hpp"

namespace meshmark {

/// True if a face around `v`, other than those on the edge v–other, would turn by so much that
/// the cosine between its normal before and after drops to `min_cosine` or below.
bool move_folds_faces(const HalfedgeMesh& mesh, HalfedgeMesh::VertexHandle v, HalfedgeMesh::VertexHandle other,
                      const Eigen::Vector3d& at, double min_cosine);

}  // namespace meshmark
