#pragma once
// Similarity attack: rotation, uniform scale and translation.

#include <cstdint>

#include "core/mesh/mesh.hpp"
#include "core/mesh/similarity.hpp"

namespace meshmark {

/// A random similarity from a seed: a uniformly random rotation, a scale in [0.5, 2] (log-
/// uniform) and a translation of up to one bounding-box diagonal.
Similarity random_similarity(const Mesh& mesh, std::uint64_t seed);

/// Applies `transform` to every vertex.
Mesh transform_mesh(const Mesh& mesh, const Similarity& transform);

}  // namespace meshmark
