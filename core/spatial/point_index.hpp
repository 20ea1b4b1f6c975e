#pragma once
// Nearest-neighbour queries over a fixed point set (a k-d tree, nanoflann). Thread-safe for
// concurrent queries once built.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

class PointIndex {
 public:
  /// Keeps a reference to `points` (#P×3): it must outlive the index.
  explicit PointIndex(const Vertices& points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  /// Index of the nearest point (of several as near, the lowest) and its squared distance; (-1, ∞)
  /// when there are no points.
  std::pair<int, double> nearest(const Eigen::Vector3d& p) const;
  /// The same answer, searched within the distance of point `hint` from the start (a point known
  /// to be near, e.g. the last ICP step's match; out of range: none): fewer branches are visited.
  std::pair<int, double> nearest(const Eigen::Vector3d& p, int hint) const;
  /// The `k` nearest points, nearest first (fewer when the set is smaller).
  std::vector<std::pair<int, double>> nearest_k(const Eigen::Vector3d& p, int k) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

/// Nearest-neighbour queries over rows of any width (descriptors). Thread-safe once built.
class FeatureIndex {
 public:
  /// Keeps a reference to `rows` (#P×D): it must outlive the index.
  explicit FeatureIndex(const Eigen::MatrixXd& rows);
  ~FeatureIndex();
  FeatureIndex(const FeatureIndex&) = delete;
  FeatureIndex& operator=(const FeatureIndex&) = delete;

  /// Index of the nearest row to `row` (D values) and its squared distance.
  std::pair<int, double> nearest(const double* row) const;
  /// The `k` nearest rows, nearest first (fewer when the set is smaller).
  std::vector<std::pair<int, double>> nearest_k(const double* row, int k) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace meshmark
