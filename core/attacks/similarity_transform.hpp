#pragma once
// Similarity attack: rotation, uniform scale and translation; and the mirror image.

#include <cstdint>

#include "core/mesh/mesh.hpp"
#include "core/mesh/similarity.hpp"

namespace meshmark {

/// A random similarity from a seed: a uniformly random rotation, a scale in [0.5, 2] (log-
/// uniform) and a translation of up to one bounding-box diagonal.
Similarity random_similarity(const Mesh& mesh, std::uint64_t seed);

/// Applies `transform` to every vertex.
Mesh transform_mesh(const Mesh& mesh, const Similarity& transform);

/// The mirror image through a plane through the mean of the vertices, its faces rewound so that
/// they face out as before (a modelling tool's mirror, an engine of the other handedness): across
/// the plane normal to `axis` (0, 1, 2), or, for axis −1, to a random direction from `seed`.
Mesh mirror_mesh(const Mesh& mesh, int axis, std::uint64_t seed);

}  // namespace meshmark
