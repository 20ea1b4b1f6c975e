#pragma once
// Resampling a suspect in the original's frame: the suspect's signed offset from the original
// surface at each original vertex, read by projecting the suspect onto the original. A vertex
// the suspect does not come near (a cropped region, a hole) is missing: an erasure, not a vote.

#include <optional>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/spatial/aabb_tree.hpp"
#include "core/watermark/vertex_offsets.hpp"

namespace meshmark {

struct DisplacementOptions {
  double search_radius = 0.02;    ///< fraction of the original's bbox diagonal
  double samples_per_vertex = 6;  ///< suspect surface samples per original vertex
  double min_share = 0.2;         ///< a vertex is read if this share of its expected samples arrived
  /// Readings beyond this many median absolute deviations are clipped (read_suspect): a few
  /// off the surface (the far side of a thin part) must not outweigh thousands.
  double outlier_clip_mads = 6;
};

struct Displacement {
  Eigen::VectorXd t;        ///< signed offset along the original's normal at each vertex (0 where missing)
  std::vector<char> found;  ///< 1 where the suspect was found near the point
  std::size_t missing = 0;
  /// The full offsets, where the suspect's vertices are the original's (vertex_offsets.hpp).
  std::optional<VertexOffsets> vertex_offsets;
};

/// The suspect's offset from the original at each original vertex, read the other way round:
/// points sampled uniformly on the (aligned) suspect are projected onto the original surface,
/// and each signed height along the original's face normal goes to the corners of the face it
/// lands on, weighted by the barycentric weights. For small displacements this is linear in the
/// suspect's geometry, so heavy noise (a jagged surface that a line crosses many times) averages
/// out instead of biasing the reading. Vertices no sample lands near are missing. Runs on
/// `threads` threads (0: the hardware's); the result does not depend on the count.
Displacement measure_by_projection(const AabbTree& original_tree, const Mesh& original, const Vertices& face_normals,
                                   const Mesh& suspect, double diagonal, const DisplacementOptions& options = {},
                                   int threads = 0);

}  // namespace meshmark
