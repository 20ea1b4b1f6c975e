#pragma once
// How stored normals follow a moved surface: each is turned by the rotation the surface's own
// normal made at its vertex, so custom normals and hard edges keep their character.

#include <Eigen/Geometry>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Per vertex: the shortest rotation taking its unit normal in `before` (V, F) to the one in
/// `after` (V2, F); the identity where either normal is zero or they are equal.
std::vector<Eigen::Quaterniond> normal_rotations(const Vertices& V, const Vertices& V2, const Faces& F);

/// `n` turned by the mean of the rotations `r` (each applied to n, the results averaged and
/// rescaled to n's length): for a normal shared by several vertices. Exactly n if all are identities.
Eigen::Vector3d rotate_shared(const Eigen::Vector3d& n, const std::vector<const Eigen::Quaterniond*>& r);

}  // namespace meshmark
