#pragma once
// Registration by the vertices a suspect kept: a copy moved, scaled, re-saved, reordered or cut
// keeps most of the original's vertex positions (up to the mark), and the distances from a vertex
// to its nearest neighbours, divided by their mean, survive any similarity. Matching those
// signatures and voting on the similarity three matches imply (RANSAC) finds the pose of a copy
// whose shape alone cannot: a ball, a bottle turned about its axis. A remeshed copy keeps no
// vertices; it registers by its shape alone (align_meshes.hpp).

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/mesh/similarity.hpp"
#include "core/registration/pose_vote.hpp"
#include "core/spatial/point_index.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

/// Neighbours each signature measures.
inline constexpr int kSignatureNeighbours = 8;

/// Per distinct position of `points`: the distances to its kSignatureNeighbours nearest other
/// positions, nearest first, divided by their mean. `distinct` receives the positions used.
Eigen::MatrixXd neighbour_signatures(const Vertices& points, Vertices& distinct, int threads);

/// The original's side, built once per model.
struct VertexSignatures {
  VertexSignatures(const Vertices& original, int threads);
  VertexSignatures(const VertexSignatures&) = delete;
  VertexSignatures& operator=(const VertexSignatures&) = delete;
  Vertices points;
  Eigen::MatrixXd signatures;
  std::unique_ptr<FeatureIndex> index;
};

struct VertexMatchOptions {
  int max_suspect_points = 3000;  ///< suspect vertices matched (evenly spread over its list)
  /// A match agrees with a pose when it lands within this share of the diagonal of its original
  /// vertex: above the mark's displacement, below the spacing of a mesh whose shape cannot register.
  double tolerance = 0.005;
  PoseVoteOptions vote;
};

struct VertexPoses {
  std::vector<Similarity> poses;
  /// Voted by the distinctive matches alone (those whose nearest signature is much nearer than
  /// the next, Lowe's ratio test): every match together found none, as where most of a copy is a
  /// regular tessellation (a blade's) whose matches are any of many alike and drown the few right
  /// ones of its distinct parts (a hilt's).
  bool distinctive = false;
};

/// The similarities mapping `suspect` onto the original by their shared vertices, best supported
/// first: more than one only where the original repeats a part the copy kept; none when too few
/// agree (a remeshed copy, another shape). Polls `control`.
VertexPoses match_vertices(const Mesh& suspect, const VertexSignatures& original, double diagonal,
                           const VertexMatchOptions& options = {}, const JobControl* control = nullptr);

}  // namespace meshmark
