#pragma once
// Nearest-neighbour queries over a fixed point set (a k-d tree, nanoflann). Thread-safe for
// concurrent queries once built.

#include <memory>

#include "core/mesh/mesh.hpp"

namespace meshmark {

class PointIndex {
 public:
  /// Keeps a reference to `points` (#P×3): it must outlive the index.
  explicit PointIndex(const Vertices& points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  /// Index of the nearest point and its squared distance.
  std::pair<int, double> nearest(const Eigen::Vector3d& p) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace meshmark
