#include "core/spatial/winding_number.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace meshmark {

namespace {

constexpr int kClusterLeafSize = 8;
// A cluster is summed as its dipole when the point is this many of its radii from its centre:
// the error then stays within a few percent of the cluster's own solid angle, plenty for a side.
constexpr double kFarRadii = 2.0;
constexpr double kFourPi = 4 * M_PI;

}  // namespace

WindingNumber::WindingNumber(const Vertices& V, const Faces& F)
    : V_(V), F_(F), order_(static_cast<std::size_t>(F.rows())) {
  std::iota(order_.begin(), order_.end(), 0);
  std::vector<Eigen::Vector3d> centroids(order_.size());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    centroids[static_cast<std::size_t>(f)] = (V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))).transpose() / 3.0;
  nodes_.reserve(2 * order_.size() / kClusterLeafSize + 2);
  if (!order_.empty()) build(0, static_cast<int>(order_.size()), centroids);
}

// Nodes in depth-first order, each node's children side by side; returns the node's index.
int WindingNumber::build(int begin, int end, const std::vector<Eigen::Vector3d>& centroids) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  summarize(nodes_.back(), begin, end);
  if (end - begin <= kClusterLeafSize) {
    nodes_[static_cast<std::size_t>(index)].first = begin;
    nodes_[static_cast<std::size_t>(index)].count = end - begin;
    return index;
  }
  Eigen::AlignedBox3d box;
  for (int i = begin; i < end; ++i)
    box.extend(centroids[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])]);
  Eigen::Index axis = 0;
  box.sizes().maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end, [&](int a, int b) {
    return centroids[static_cast<std::size_t>(a)][axis] < centroids[static_cast<std::size_t>(b)][axis];
  });
  const int children = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[static_cast<std::size_t>(index)].first = children;
  // Build each child in place of its reserved slot: its subtree follows the two slots.
  for (int side = 0; side < 2; ++side) {
    const int built = build(side == 0 ? begin : middle, side == 0 ? middle : end, centroids);
    nodes_[static_cast<std::size_t>(children) + static_cast<std::size_t>(side)] =
        nodes_[static_cast<std::size_t>(built)];
  }
  return index;
}

void WindingNumber::summarize(Node& node, int begin, int end) const {
  double area = 0;
  node.centre.setZero();
  node.area_normal.setZero();
  for (int i = begin; i < end; ++i) {
    const int f = order_[static_cast<std::size_t>(i)];
    const Eigen::Vector3d a = V_.row(F_(f, 0)), b = V_.row(F_(f, 1)), c = V_.row(F_(f, 2));
    const Eigen::Vector3d area_vector = 0.5 * (b - a).cross(c - a);
    const double size = area_vector.norm();
    node.area_normal += area_vector;
    node.centre += size * (a + b + c) / 3.0;
    area += size;
  }
  if (area > 0) node.centre /= area;
  else if (end > begin) node.centre = V_.row(F_(order_[static_cast<std::size_t>(begin)], 0)).transpose();
  node.radius = 0;
  for (int i = begin; i < end; ++i)
    for (int k = 0; k < 3; ++k)
      node.radius =
          std::max(node.radius, (V_.row(F_(order_[static_cast<std::size_t>(i)], k)).transpose() - node.centre).norm());
}

// Van Oosterom and Strackee's formula for the signed solid angle of a triangle.
double WindingNumber::triangle_solid_angle(int face, const Eigen::Vector3d& point) const {
  const Eigen::Vector3d a = V_.row(F_(face, 0)).transpose() - point, b = V_.row(F_(face, 1)).transpose() - point,
                        c = V_.row(F_(face, 2)).transpose() - point;
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2 * std::atan2(numerator, denominator);
}

double WindingNumber::at(const Eigen::Vector3d& point) const {
  if (nodes_.empty()) return 0;
  double solid_angle = 0;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& node = nodes_[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    const Eigen::Vector3d to_centre = node.centre - point;
    const double distance = to_centre.norm();
    if (distance > kFarRadii * node.radius) {
      solid_angle += to_centre.dot(node.area_normal) / (distance * distance * distance);
    } else if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i)
        solid_angle += triangle_solid_angle(order_[static_cast<std::size_t>(i)], point);
    } else {
      stack.push_back(node.first);
      stack.push_back(node.first + 1);
    }
  }
  return solid_angle / kFourPi;
}

}  // namespace meshmark
