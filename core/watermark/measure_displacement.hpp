#pragma once
// Resampling a suspect in the original's frame: for each point p with unit normal n of the
// original, where does the (aligned) suspect surface cross the line p + t·n, nearest to t = 0?
// The signed t is the suspect's displacement along the normal there. No crossing within the
// search radius (a cropped region, a hole) is a missing sample: an erasure, not a vote.

#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/spatial/aabb_tree.hpp"

namespace meshmark {

struct DisplacementOptions {
  double search_radius = 0.02;   ///< fraction of the original's bbox diagonal
  /// Without a crossing, the closest suspect point within this fraction of the radius counts
  /// (its offset projected on the normal): lines that graze a fold or an edge still read.
  double closest_fallback = 0.25;
};

struct Displacement {
  Eigen::VectorXd t;          ///< signed displacement along each normal (0 where missing)
  std::vector<char> found;    ///< 1 where the suspect was found near the point
  std::size_t missing = 0;
};

/// `suspect_tree` indexes the suspect already mapped into the original's frame.
Displacement measure_displacement(const AabbTree& suspect_tree, const Vertices& points, const Vertices& normals,
                                  double diagonal, const DisplacementOptions& options = {});

}  // namespace meshmark
