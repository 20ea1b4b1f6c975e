#pragma once
// Remeshing attack: isotropic remeshing (Botsch and Kobbelt 2004) towards a target edge length:
// long edges split, short ones collapsed, edges flipped towards valence 6, vertices relaxed
// tangentially and projected back onto the input surface. No vertex of the input survives; the
// surface stays (close to) the same.

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct RemeshOptions {
  double target_edge_length = 0;  ///< 0: the input's mean edge length
  int iterations = 5;
};

/// Needs a manifold mesh (throws std::invalid_argument otherwise). Deterministic.
Mesh remesh(const Mesh& mesh, const RemeshOptions& options = {});

}  // namespace meshmark
