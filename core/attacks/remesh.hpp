#pragma once
// Remeshing attack: isotropic remeshing (Botsch and Kobbelt 2004) towards a target edge length:
// long edges split, short ones collapsed, edges flipped towards valence 6, vertices relaxed
// tangentially and projected back onto the input surface. Boundaries keep their outline (their
// vertices are not relaxed and never merge inwards). No interior vertex of the input survives;
// the surface stays (close to) the same.

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct RemeshOptions {
  double target_edge_length = 0;  ///< 0: the input's mean edge length
  int iterations = 5;
  /// Collapses and flips that would put the surface farther than this from the input (a
  /// fraction of its bounding-box diagonal) are skipped, as remeshers with a surface-distance
  /// check do (MeshLab's isotropic remeshing): a copy that loses its thin tips is not a copy.
  double max_surface_distance = 1e-3;
};

/// Non-manifold spots are cut apart first. Throws std::invalid_argument for a mesh whose edges are
/// below its coordinates' precision (nothing left to remesh). Deterministic.
Mesh remesh(const Mesh& mesh, const RemeshOptions& options = {});

}  // namespace meshmark
