#pragma once
// The generalized winding number of a triangle soup (Jacobson, Kavan and Sorkine-Hornung 2013):
// the signed solid angle the surface subtends at a point, over 4π. 1 inside a closed surface
// wound outward, 0 outside, and a smooth "insideness" for a surface with holes, which its
// level 1/2 closes. Far triangles are summed as one dipole per cluster (Barill et al. 2018).
// Built once, then queried concurrently (queries do not modify it).

#include <Eigen/Core>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

class WindingNumber {
 public:
  /// Keeps references to V and F: they must outlive it.
  WindingNumber(const Vertices& V, const Faces& F);

  double at(const Eigen::Vector3d& point) const;

 private:
  struct Node {
    Eigen::Vector3d centre;       ///< area-weighted centroid of its triangles
    Eigen::Vector3d area_normal;  ///< the sum of its triangles' area vectors
    double radius = 0;            ///< of the ball about `centre` holding its triangles
    int first = 0, count = 0;     ///< leaf: its triangles in order_; inner: count 0, children first and first + 1
  };
  int build(int begin, int end, const std::vector<Eigen::Vector3d>& centroids);
  void summarize(Node& node, int begin, int end) const;
  double triangle_solid_angle(int face, const Eigen::Vector3d& point) const;

  const Vertices& V_;
  const Faces& F_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace meshmark
