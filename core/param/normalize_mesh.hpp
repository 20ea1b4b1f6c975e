#pragma once
// Moving a mesh to a canonical position and size, and back.

#include <Eigen/Core>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// x_normalized = (x − center) · scale.
struct Normalization {
  Eigen::RowVector3d center = Eigen::RowVector3d::Zero();
  double scale = 1.0;
};

/// The transform that puts the area-weighted centroid at the origin and makes the area 1.
Normalization unit_area_normalization(const Vertices& V, const Faces& F);

/// Applies `n` to every vertex.
Vertices apply(const Normalization& n, const Vertices& V);

}  // namespace meshmark
