#pragma once
// Reading a suspect whose vertices are the original's (reordered, moved, a little noise): each
// original vertex's full 3-D offset to the suspect vertex it corresponds to. A scheme whose
// carriers move vertices off the normal (the paper's vector coefficients) reads them whole this
// way; a reading by projection sees only the normal part.

#include <optional>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct VertexOffsetOptions {
  /// A pair corresponds when each is the other's nearest vertex within this share of the
  /// original's median edge length.
  double tolerance_edges = 0.5;
  /// A vertex paired through a shared face (the rest's partners name it) lies within this many
  /// median edges of its partner.
  double face_reach_edges = 2;
  /// The reading is used only when this share of the original's vertices corresponds.
  double min_share = 0.9;
  /// Threads for the nearest-vertex queries (0: the hardware's); the pairs do not depend on it.
  int threads = 1;
};

struct VertexOffsets {
  Vertices offset;                 ///< #V×3: suspect minus original (0 where not corresponded)
  std::vector<char> corresponded;  ///< 1 where a suspect vertex corresponds
};

/// The offsets of `suspect` at the original's vertices: pairs are found between `original` and
/// `aligned` (the suspect registered to it, perhaps unbent; its faces are the suspect's), as
/// mutual nearest vertices (at least `min_share` of them), mended through the faces the copy
/// shares with the original; the offsets are measured on
/// the suspect moved by the best similarity between the pairs (a field fitted by registration
/// could take up a coarse carrier). Nothing when too few vertices correspond (a remeshed,
/// simplified or cropped copy).
std::optional<VertexOffsets> corresponding_offsets(const Mesh& original, const Mesh& aligned, const Vertices& suspect,
                                                   double median_edge, const VertexOffsetOptions& options = {});

/// The same for a suspect that kept the original's vertex order (registered by it): vertex i is
/// original vertex i wherever `aligned` puts it within `tolerance`. On a dense mesh a mark moves
/// vertices further than half an edge, where mutual nearest neighbours no longer pair them.
std::optional<VertexOffsets> offsets_in_order(const Vertices& original, const Vertices& aligned,
                                              const Vertices& suspect, double tolerance,
                                              const VertexOffsetOptions& options = {});

/// The median edge length of `mesh`: the scale correspondences are judged by.
double median_edge_length(const Mesh& mesh);

/// An orthonormal basis (#V·3 × 7, the column-major layout of a #V×3 field) of the offsets a
/// small similarity adds at the vertices marked `corresponded`: translation, rotation, scale.
Eigen::MatrixXd similarity_fields(const Vertices& original, const std::vector<char>& corresponded);

}  // namespace meshmark
