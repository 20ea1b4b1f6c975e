#include "core/spatial/point_index.hpp"

#include <bit>
#include <cstdint>
#include <limits>
#include <nanoflann.hpp>

namespace meshmark {

// The rows of a matrix as nanoflann reads them (external linkage: the trees below hold it).
template <typename Matrix>
struct RowDataset {
  const Matrix& points;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points.rows()); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const {
    return points(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(d));
  }
  template <typename Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

struct PointIndex::Tree {
  using Dataset = RowDataset<Vertices>;
  using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Dataset>, Dataset, 3, int>;

  explicit Tree(const Vertices& points) : data{points}, index(3, data, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
  Dataset data;
  KdTree index;
};

PointIndex::PointIndex(const Vertices& points) : tree_(std::make_unique<Tree>(points)) {}
PointIndex::~PointIndex() = default;

namespace {

// nanoflann's result set for the one nearest point, which may start from a known point's distance.
// Points exactly as near as the best are offered too (`reach`), so that a tie goes to the lower
// index whichever the search met first, with a hint or without.
struct NearestWithin {
  double best;
  int index;
  double reach;  // widened(best), kept: nanoflann asks for it at every node
  NearestWithin(double distance_squared, int i) : best(distance_squared), index(i), reach(widened(best)) {}
  static double widened(double d) {  // the next double up (std::nextafter, without the call)
    return d < std::numeric_limits<double>::infinity() ? std::bit_cast<double>(std::bit_cast<std::uint64_t>(d) + 1) : d;
  }
  bool full() const { return true; }
  double worstDist() const { return reach; }
  bool addPoint(double distance_squared, int i) {
    if (distance_squared < best || (distance_squared == best && i < index))
      best = distance_squared, index = i, reach = widened(best);
    return true;
  }
};

}  // namespace

std::pair<int, double> PointIndex::nearest(const Eigen::Vector3d& p) const {
  NearestWithin result(std::numeric_limits<double>::infinity(), -1);
  tree_->index.findNeighbors(result, p.data(), nanoflann::SearchParams());
  return {result.index, result.best};
}

std::pair<int, double> PointIndex::nearest(const Eigen::Vector3d& p, int hint) const {
  if (hint < 0 || hint >= tree_->data.points.rows()) return nearest(p);
  // The tree's own metric: the hint's distance has the bits the search would give it.
  NearestWithin result(tree_->index.distance.evalMetric(p.data(), static_cast<std::size_t>(hint), 3), hint);
  tree_->index.findNeighbors(result, p.data(), nanoflann::SearchParams());
  return {result.index, result.best};
}

std::vector<std::pair<int, double>> PointIndex::nearest_k(const Eigen::Vector3d& p, int k) const {
  std::vector<int> index(static_cast<std::size_t>(k));
  std::vector<double> distance_squared(static_cast<std::size_t>(k));
  const std::size_t found =
      tree_->index.knnSearch(p.data(), static_cast<std::size_t>(k), index.data(), distance_squared.data());
  std::vector<std::pair<int, double>> out;
  for (std::size_t i = 0; i < found; ++i) out.emplace_back(index[i], distance_squared[i]);
  return out;
}

struct FeatureIndex::Tree {
  using Dataset = RowDataset<Eigen::MatrixXd>;
  using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Dataset>, Dataset, -1, int>;

  explicit Tree(const Eigen::MatrixXd& rows)
      : data{rows}, index(static_cast<int>(rows.cols()), data, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
  Dataset data;
  KdTree index;
};

FeatureIndex::FeatureIndex(const Eigen::MatrixXd& rows) : tree_(std::make_unique<Tree>(rows)) {}
FeatureIndex::~FeatureIndex() = default;

std::pair<int, double> FeatureIndex::nearest(const double* row) const {
  int index = -1;
  double distance_squared = 0;
  tree_->index.knnSearch(row, 1, &index, &distance_squared);
  return {index, distance_squared};
}

std::vector<std::pair<int, double>> FeatureIndex::nearest_k(const double* row, int k) const {
  std::vector<int> index(static_cast<std::size_t>(k));
  std::vector<double> distance_squared(static_cast<std::size_t>(k));
  const auto found = tree_->index.knnSearch(row, static_cast<std::size_t>(k), index.data(), distance_squared.data());
  std::vector<std::pair<int, double>> out;
  for (std::size_t i = 0; i < found; ++i) out.emplace_back(index[i], distance_squared[i]);
  return out;
}

}  // namespace meshmark
