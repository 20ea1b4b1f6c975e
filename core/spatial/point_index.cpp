#include "core/spatial/point_index.hpp"

#include <nanoflann.hpp>

namespace meshmark {

// The tree and the adaptor nanoflann reads the points through; nested, not in an anonymous
// namespace, because Tree has external linkage.
struct PointIndex::Tree {
  struct Dataset {
    const Vertices& points;
    std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points.rows()); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const {
      return points(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(d));
    }
    template <typename Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Dataset>, Dataset, 3, int>;

  explicit Tree(const Vertices& points) : data{points}, index(3, data, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
  Dataset data;
  KdTree index;
};

PointIndex::PointIndex(const Vertices& points) : tree_(std::make_unique<Tree>(points)) {}
PointIndex::~PointIndex() = default;

std::pair<int, double> PointIndex::nearest(const Eigen::Vector3d& p) const {
  int index = -1;
  double distance_squared = 0;
  tree_->index.knnSearch(p.data(), 1, &index, &distance_squared);
  return {index, distance_squared};
}

}  // namespace meshmark
