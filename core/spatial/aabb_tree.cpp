#include "core/spatial/aabb_tree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <limits>
#include <stdexcept>

#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

constexpr int kLeafSize = 4;

// The leaves a subtree of `faces` faces has: all full but the last.
std::size_t leaves_for(int faces) { return static_cast<std::size_t>((faces + kLeafSize - 1) / kLeafSize); }
constexpr int kParallelBuildFaces = 1 << 16;  // below, a thread costs more than half the subtree's build

// A depth-first traversal's pending nodes, on the stack frame: queries run by the million and a
// heap allocation each cost more than the search. Median splits keep the tree's depth at
// log2(faces / kLeafSize) + 1 and a traversal holds at most one node per level plus the current.
template <typename Entry>
class TraversalStack {
 public:
  void push(const Entry& e) {
    if (size_ == entries_.size()) throw std::logic_error("AABB traversal deeper than a median-split tree can be");
    entries_[size_++] = e;
  }
  Entry pop() { return entries_[--size_]; }
  bool empty() const { return size_ == 0; }

 private:
  std::array<Entry, 66> entries_;
  std::size_t size_ = 0;
};

// Möller–Trumbore, both sides; the barycentric test allows a hair of slack so that a line
// through a shared edge is not lost between two triangles.
bool intersect_triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b, const Eigen::Vector3d& c, double& t, Eigen::Vector3d& bary) {
  constexpr double slack = 1e-12;
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d pv = d.cross(e2);
  const double det = e1.dot(pv);
  if (det == 0) return false;
  const double inv = 1.0 / det;
  const Eigen::Vector3d tv = o - a;
  const double u = tv.dot(pv) * inv;
  if (u < -slack || u > 1 + slack) return false;
  const Eigen::Vector3d qv = tv.cross(e1);
  const double v = d.dot(qv) * inv;
  if (v < -slack || u + v > 1 + slack) return false;
  t = e2.dot(qv) * inv;
  bary = Eigen::Vector3d(1 - u - v, u, v);
  return true;
}

// The parameter interval where the line o + t d is inside the box (empty if t0 > t1).
void slab(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& o, const Eigen::Vector3d& inv_d, double& t0,
          double& t1) {
  for (int k = 0; k < 3; ++k) {
    double a = (box.min()[k] - o[k]) * inv_d[k], b = (box.max()[k] - o[k]) * inv_d[k];
    if (std::isnan(a) || std::isnan(b)) {  // direction parallel to the slab, origin on its plane
      a = -std::numeric_limits<double>::infinity();
      b = std::numeric_limits<double>::infinity();
    }
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
}

}  // namespace

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c, Eigen::Vector3d& bary) {
  // Voronoi regions of the vertices, edges and face (Ericson, Real-Time Collision Detection §5.1.5).
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return bary = {1, 0, 0}, a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bary = {0, 1, 0}, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return bary = {1 - v, v, 0}, a + v * ab;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return bary = {0, 0, 1}, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return bary = {1 - w, 0, w}, a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return bary = {0, 1 - w, w}, b + w * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  bary = {1 - v - w, v, w};
  return a + ab * v + ac * w;
}

// Centroids in single precision: they only choose the splits (any split answers the same), and
// the items are the build's largest array (2.2M vertices: 70 MB where doubles took 140).
struct AabbTree::BuildItem {
  Eigen::Vector3f centroid;
  int face;
};

AabbTree::AabbTree(const Vertices& V, const Faces& F, int threads) : V_(V), F_(F) {
  const int n = static_cast<int>(F.rows());
  std::vector<BuildItem> items(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f)
    items[f] = {((V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))).transpose() / 3.0).cast<float>(), f};
  nodes_.reserve(2 * leaves_for(n));
  if (n > 0) build(nodes_, 0, n, items, resolve_threads(threads));
  order_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order_[i] = items[i].face;
}

// Splits at the median centroid along the widest axis of the centroids. A leaf's box comes from
// its triangles, an inner node's from its two children: each vertex is read once, not per level.
// Appends the subtree to `nodes` in depth-first order (its indices relative to nodes' start) and
// returns its root's index. A large subtree's right half is built on another thread while
// `threads` allow, into its own nodes appended after the left's: the same tree as on one thread.
int AabbTree::build(std::vector<Node>& nodes, int begin, int end, std::vector<BuildItem>& items, int threads) const {
  const int index = static_cast<int>(nodes.size());
  nodes.emplace_back();
  if (end - begin <= kLeafSize) {
    Eigen::AlignedBox3d box;
    for (int i = begin; i < end; ++i)
      for (int k = 0; k < 3; ++k) box.extend(V_.row(F_(items[i].face, k)).transpose());
    nodes[index] = {box, begin, end - begin};
    return index;
  }
  Eigen::AlignedBox3f centre_box;
  for (int i = begin; i < end; ++i) centre_box.extend(items[i].centroid);
  int axis;
  centre_box.sizes().maxCoeff(&axis);
  // The left half holds a whole number of full leaves, at least half of the faces: every leaf
  // but one is full, and the tree has about half a node per face. Halving the count exactly left
  // leaves of two faces on some sizes, a node per face (2.2M vertices: 250 MB a tree).
  const int mid = begin + kLeafSize * ((leaves_for(end - begin) + 1) / 2);
  std::nth_element(
      items.begin() + begin, items.begin() + mid, items.begin() + end, [axis](const BuildItem& x, const BuildItem& y) {
        return x.centroid[axis] != y.centroid[axis] ? x.centroid[axis] < y.centroid[axis] : x.face < y.face;
      });
  if (threads < 2 || end - begin < kParallelBuildFaces) {
    const int left = build(nodes, begin, mid, items, 1);
    const int right = build(nodes, mid, end, items, 1);
    nodes[index] = {nodes[left].box.merged(nodes[right].box), right, 0};
    return index;
  }
  std::vector<Node> right_nodes;
  auto right = std::async(std::launch::async, [&] { build(right_nodes, mid, end, items, threads / 2); });
  const int left = build(nodes, begin, mid, items, threads - threads / 2);
  right.get();
  const int offset = static_cast<int>(nodes.size());
  for (Node node : right_nodes) {
    if (node.count == 0) node.first += offset;  // an inner node's right child
    nodes.push_back(node);
  }
  nodes[index] = {nodes[left].box.merged(nodes[offset].box), offset, 0};
  return index;
}

void AabbTree::visit_leaf_hits(const Node& node, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                               double t_lo, double t_hi, std::optional<TriangleHit>& best, double& best_t) const {
  for (int i = node.first; i < node.first + node.count; ++i) {
    const int f = order_[i];
    double t;
    Eigen::Vector3d bary;
    if (!intersect_triangle(origin, direction, V_.row(F_(f, 0)), V_.row(F_(f, 1)), V_.row(F_(f, 2)), t, bary)) continue;
    if (t < t_lo || t > t_hi) continue;
    if (t < best_t || (t == best_t && best && f < best->face)) {
      best_t = t;
      best = TriangleHit{f, t, bary, origin + t * direction, 0};
    }
  }
}

std::optional<TriangleHit> AabbTree::first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                               double t_min, double t_max) const {
  std::optional<TriangleHit> best;
  if (nodes_.empty()) return best;
  const Eigen::Vector3d inv_d = direction.cwiseInverse();
  double best_t = std::numeric_limits<double>::infinity();
  TraversalStack<int> stack;
  stack.push(0);
  while (!stack.empty()) {
    const int ni = stack.pop();
    const Node& node = nodes_[ni];
    double t0 = t_min, t1 = std::min(t_max, best_t);
    slab(node.box, origin, inv_d, t0, t1);
    if (t0 > t1) continue;
    if (node.count > 0) {
      visit_leaf_hits(node, origin, direction, t_min, t_max, best, best_t);
    } else {
      stack.push(node.first);
      stack.push(ni + 1);
    }
  }
  return best;
}

std::optional<TriangleHit> AabbTree::closest_point(const Eigen::Vector3d& p, double max_distance, int hint) const {
  std::optional<TriangleHit> best;
  if (nodes_.empty()) return best;
  double best_d2 = max_distance * max_distance;
  if (hint >= 0 && hint < F_.rows()) {
    Eigen::Vector3d bary;
    const Eigen::Vector3d q =
        closest_point_on_triangle(p, V_.row(F_(hint, 0)), V_.row(F_(hint, 1)), V_.row(F_(hint, 2)), bary);
    // The least (distance, face) wins below whatever the visiting order, so a hint changes no answer.
    if (const double d2 = (q - p).squaredNorm(); d2 < best_d2) best_d2 = d2, best = TriangleHit{hint, 0, bary, q, d2};
  }
  TraversalStack<std::pair<double, int>> stack;
  stack.push({nodes_[0].box.squaredExteriorDistance(p), 0});
  while (!stack.empty()) {
    const auto [box_d2, ni] = stack.pop();
    if (box_d2 > best_d2) continue;
    const Node& node = nodes_[ni];
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int f = order_[i];
        Eigen::Vector3d bary;
        const Eigen::Vector3d q =
            closest_point_on_triangle(p, V_.row(F_(f, 0)), V_.row(F_(f, 1)), V_.row(F_(f, 2)), bary);
        const double d2 = (q - p).squaredNorm();
        if (d2 < best_d2 || (d2 == best_d2 && best && f < best->face)) {
          best_d2 = d2;
          best = TriangleHit{f, 0, bary, q, d2};
        }
      }
      continue;
    }
    // Visit the nearer child first: push it last.
    const int left = ni + 1, right = node.first;
    const double dl = nodes_[left].box.squaredExteriorDistance(p), dr = nodes_[right].box.squaredExteriorDistance(p);
    if (dl <= dr) {
      stack.push({dr, right});
      stack.push({dl, left});
    } else {
      stack.push({dl, left});
      stack.push({dr, right});
    }
  }
  return best;
}

}  // namespace meshmark
