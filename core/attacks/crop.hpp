#pragma once
// Cropping attack: the faces on one side of a random plane are removed until the given
// fraction of the surface area is gone; vertices no face uses any more are dropped. The result
// is open (it has a boundary) and may fall apart into pieces.

#include <cstdint>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Removes `fraction` (in [0, 1)) of the area. Deterministic for a seed.
Mesh crop(const Mesh& mesh, double fraction, std::uint64_t seed);

/// Keeps the listed faces and the vertices they use (renumbered in their original order).
Mesh keep_faces(const Mesh& mesh, const std::vector<int>& faces);

}  // namespace meshmark
