#pragma once
// The proof that a map to the sphere is bijective: every spherical triangle positively oriented
// (exact sign of det(a, b, c)) and the signed spherical areas summing to 4π (degree 1).

#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct SphericalMapCheck {
  std::size_t flipped_faces = 0;  ///< faces with det(a, b, c) ≤ 0, decided exactly
  double degree = 0;              ///< Σ signed spherical areas / 4π
  std::vector<int> flipped;       ///< indices of the flipped faces

  /// True when the map is a bijection onto the sphere.
  bool bijective() const;
};

/// `S` holds the vertex images, one per row, on the unit sphere (normalized before the areas
/// are summed); `F` the faces.
SphericalMapCheck check_spherical_map(const Vertices& S, const Faces& F);

}  // namespace meshmark
