#pragma once
// A bounding-volume hierarchy over the triangles of a mesh: nearest ray or line crossing, and
// closest point. Built once, then queried concurrently from any number of threads (queries do
// not modify the tree).

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct TriangleHit {
  int face = -1;
  double t = 0;                                    ///< ray/line parameter (hits), or 0
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();  ///< weights of F(face, 0..2)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance_squared = 0;  ///< closest-point queries
};

class AabbTree {
 public:
  /// Keeps references to V and F: they must outlive the tree. Built on up to `threads` threads
  /// (0: the hardware's); the tree is the same on any count.
  AabbTree(const Vertices& V, const Faces& F, int threads = 0);

  /// The crossing of origin + t·direction with the smallest t in [t_min, t_max].
  std::optional<TriangleHit> first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min,
                                       double t_max) const;

  /// The closest point of the surface to p, if closer than max_distance. A `hint` face (e.g. the
  /// previous query's, for points that come in order along a surface) bounds the search from the
  /// start; the answer is the same with or without it.
  std::optional<TriangleHit> closest_point(const Eigen::Vector3d& p,
                                           double max_distance = std::numeric_limits<double>::infinity(),
                                           int hint = -1) const;

  /// Nodes in the tree: 2·⌈faces / 4⌉ − 1, every leaf full but one (what its memory is).
  std::size_t node_count() const { return nodes_.size(); }

  const Vertices& vertices() const { return V_; }
  const Faces& faces() const { return F_; }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0;  ///< leaf: first index into order_; inner: the right child (the left is the next node)
    int count = 0;  ///< leaf: number of triangles; inner: 0
  };
  struct BuildItem;  // a face and its centroid, kept together so that a split reads them in order
  int build(std::vector<Node>& nodes, int begin, int end, std::vector<BuildItem>& items, int threads) const;
  void visit_leaf_hits(const Node& node, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_lo,
                       double t_hi, std::optional<TriangleHit>& best, double& best_t) const;

  const Vertices& V_;
  const Faces& F_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

/// The point of triangle (a, b, c) closest to p, with its barycentric weights.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c, Eigen::Vector3d& bary);

}  // namespace meshmark
