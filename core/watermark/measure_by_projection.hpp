#pragma once
// Resampling a suspect in the original's frame: for each point p with unit normal n of the
// original, where does the (aligned) suspect surface cross the line p + t·n, nearest to t = 0?
// The signed t is the suspect's displacement along the normal there. No crossing within the
// search radius (a cropped region, a hole) is a missing sample: an erasure, not a vote.

#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/spatial/aabb_tree.hpp"

namespace meshmark {

enum class ReadingMethod {
  projection,  ///< suspect surface samples projected onto the original (linear; the default)
  ray,         ///< the suspect's nearest crossing along each original vertex normal
};

struct DisplacementOptions {
  ReadingMethod method = ReadingMethod::projection;
  double search_radius = 0.02;   ///< fraction of the original's bbox diagonal
  double samples_per_vertex = 6; ///< projection: suspect surface samples per original vertex
  double min_share = 0.2;        ///< projection: a vertex is read if this share of its expected samples arrived
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

/// The suspect's offset from the original at each original vertex, read the other way round:
/// points sampled uniformly on the (aligned) suspect are projected onto the original surface,
/// and each signed height along the original's face normal goes to the corners of the face it
/// lands on, weighted by the barycentric weights. For small displacements this is linear in the
/// suspect's geometry, so heavy noise (a jagged surface that a line crosses many times) averages
/// out instead of biasing the reading. Vertices no sample lands near are missing.
Displacement measure_by_projection(const AabbTree& original_tree, const Mesh& original, const Vertices& face_normals,
                                   const Mesh& suspect, double diagonal, const DisplacementOptions& options = {});

}  // namespace meshmark
