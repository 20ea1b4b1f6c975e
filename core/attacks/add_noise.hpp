#pragma once
// Noise attack: every coordinate of every vertex moved by an independent uniform amount in
// [−a, a], with a given as a percentage of the bounding-box diagonal (the paper's measure) or of
// the mean distance from the vertices to their centroid (the benchmark's).

#include <cstdint>
#include <string>

#include "core/mesh/mesh.hpp"

namespace meshmark {

enum class NoiseReference { bbox_diagonal, centroid_distance };
NoiseReference parse_noise_reference(const std::string& name);  ///< "bbox" or "centroid"

Mesh add_noise(const Mesh& mesh, double amplitude_percent, NoiseReference reference, std::uint64_t seed);

/// The length that `reference` measures on the mesh.
double noise_reference_length(const Mesh& mesh, NoiseReference reference);

}  // namespace meshmark
