#pragma once
// Laplacian smoothing attack: `iterations` times, every vertex moves by λ times the vector to
// the average of its neighbours (the benchmark uses λ = 0.03).

#include "core/mesh/mesh.hpp"

namespace meshmark {

Mesh laplacian_smooth(const Mesh& mesh, double lambda, int iterations);

}  // namespace meshmark
