#pragma once
// Laplacian smoothing: `iterations` times, every vertex moves by λ times the vector to the
// average of its neighbours. The smoothing attack (the benchmark uses λ = 0.03) and the
// detector's model of the shrinkage it causes (watermark/nuisance_fields) both use it.

#include "core/mesh/mesh.hpp"
#include "core/mesh/vertex_neighbors.hpp"

namespace meshmark {

/// On `threads` threads (0: the hardware's); the result does not depend on the count.
Mesh laplacian_smooth(const Mesh& mesh, double lambda, int iterations, int threads = 0);

/// The same on vertex positions whose neighbours are already known (smoothing in several rounds).
Vertices laplacian_smooth(const Vertices& V, const VertexNeighbors& nb, double lambda, int iterations, int threads = 0);

}  // namespace meshmark
