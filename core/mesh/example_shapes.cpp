#include "core/mesh/example_shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace meshmark {

namespace {

// How far along `direction` a horn of length `length` and angular radius `width` (radians)
// lifts the unit direction `u`: a smooth dome in angle, steep enough to be a limb.
double horn(const Eigen::Vector3d& u, const Eigen::Vector3d& direction, double length, double width) {
  const double angle = std::acos(std::clamp(u.dot(direction.normalized()), -1.0, 1.0));
  if (angle >= width) return 0;
  const double t = 1 - (angle / width) * (angle / width);
  return length * t * std::sqrt(t);
}

}  // namespace

Mesh icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& [a, b, c] : f) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.push_back({a, ab, ca});
      next.push_back({ab, b, bc});
      next.push_back({ca, bc, c});
      next.push_back({ab, bc, ca});
    }
    f.swap(next);
  }
  Mesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) mesh.V.row(static_cast<Eigen::Index>(i)) = v[i];
  mesh.F.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 3; ++k) mesh.F(static_cast<Eigen::Index>(i), k) = f[i][k];
  return mesh;
}

Mesh side_by_side(const Mesh& a, const Mesh& b, double shift) {
  Mesh both;
  both.V.resize(a.V.rows() + b.V.rows(), 3);
  both.V << a.V, (b.V.array() + shift).matrix();
  both.F.resize(a.F.rows() + b.F.rows(), 3);
  both.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return both;
}

Mesh uneven_ball(int levels) {
  Mesh ball = icosphere(levels);
  const double edge = (ball.V.row(ball.F(0, 0)) - ball.V.row(ball.F(0, 1))).norm();
  for (Eigen::Index i = 0; i < ball.V.rows(); ++i) {
    // A slide from the vertex's index alone (no generator whose sequence a library may change).
    const double a = std::sin(12.9898 * static_cast<double>(i + 1)) * 43758.5453,
                 b = std::sin(78.233 * static_cast<double>(i + 1)) * 12345.6789;
    const Eigen::Vector3d slide(a - std::floor(a) - 0.5, b - std::floor(b) - 0.5, std::sin(static_cast<double>(i)));
    const Eigen::Vector3d u = ball.V.row(i).transpose();
    const Eigen::Vector3d tangent = slide - slide.dot(u) * u;
    if (tangent.norm() < 1e-6) continue;
    ball.V.row(i) = (u + 0.2 * edge * tangent.normalized() * std::abs(a - std::floor(a))).normalized().transpose();
  }
  return ball;
}

Mesh cube() {
  Mesh mesh;
  mesh.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) mesh.V.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  mesh.F.resize(12, 3);
  mesh.F << 0, 2, 1, 1, 2, 3,  // z = 0, normal -z
      4, 5, 6, 5, 7, 6,        // z = 1
      0, 1, 4, 1, 5, 4,        // y = 0
      2, 6, 3, 3, 6, 7,        // y = 1
      0, 4, 2, 2, 4, 6,        // x = 0
      1, 3, 5, 3, 7, 5;        // x = 1
  return mesh;
}

Mesh torus(int rings, int segments) { return lumpy_torus(rings, segments, 0); }

Mesh lumpy_torus(int rings, int segments, double lumps) {
  Mesh mesh;
  mesh.V.resize(rings * segments, 3);
  mesh.F.resize(2 * rings * segments, 3);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double u = 2 * M_PI * i / rings, w = 2 * M_PI * j / segments;
      // lumps > 0: a tube whose thickness and path vary around the ring, so that no rotation
      // maps the shape onto itself.
      const double tube = 1 + lumps * (0.3 * std::sin(u) + 0.15 * std::cos(3 * u) + 0.05 * std::sin(7 * u + 2 * w));
      const double ring = 2 + lumps * 0.3 * std::cos(2 * u);
      mesh.V.row(i * segments + j) << (ring + tube * std::cos(w)) * std::cos(u),
          (ring + tube * std::cos(w)) * std::sin(u) * (1 - 0.15 * lumps),
          tube * std::sin(w) + lumps * 0.3 * std::sin(u);
      const int a = i * segments + j, b = ((i + 1) % rings) * segments + j,
                c = ((i + 1) % rings) * segments + (j + 1) % segments, d = i * segments + (j + 1) % segments;
      mesh.F.row(2 * a) << a, b, c;
      mesh.F.row(2 * a + 1) << a, c, d;
    }
  return mesh;
}

Mesh creature(int levels) {
  Mesh mesh = icosphere(levels);
  struct Limb {
    Eigen::Vector3d direction;
    double length, width;
  };
  const Limb limbs[] = {{{0.5, -0.4, -1}, 1.2, 0.22}, {{-0.5, -0.4, -1}, 1.2, 0.22},  // legs
                        {{0.4, 0.9, 0.5}, 0.8, 0.18}, {{-0.4, 0.9, 0.5}, 0.8, 0.18},  // ears
                        {{0, -0.3, 1}, 1.6, 0.16},    {{1, 0.1, 0.1}, 0.9, 0.25}};    // tail, snout
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    const Eigen::Vector3d u = mesh.V.row(i).transpose();
    double radius = 1 + 0.12 * std::sin(3 * u.x()) * std::cos(2 * u.y()) + 0.08 * std::cos(5 * u.z()) +
                    0.01 * std::sin(23 * u.x() + 17 * u.y()) * std::cos(19 * u.z());
    for (const Limb& limb : limbs) radius += horn(u, limb.direction, limb.length, limb.width);
    mesh.V.row(i) = (radius * u).transpose().cwiseProduct(Eigen::RowVector3d(1.4, 1.0, 0.9));
  }
  return mesh;
}

Mesh with_holes(const Mesh& mesh, int holes, double radius) {
  std::vector<Eigen::RowVector3d> centers;
  for (int h = 0; h < holes; ++h) centers.push_back(mesh.V.row((2 * h + 1) * mesh.V.rows() / (2 * holes)));
  std::vector<Eigen::Index> kept;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::RowVector3d c = (mesh.V.row(mesh.F(f, 0)) + mesh.V.row(mesh.F(f, 1)) + mesh.V.row(mesh.F(f, 2))) / 3;
    bool inside = false;
    for (const auto& center : centers) inside = inside || (c - center).norm() < radius;
    if (!inside) kept.push_back(f);
  }
  // Vertices no kept face uses go too, as when a tool deletes faces and saves.
  std::vector<int> index(static_cast<std::size_t>(mesh.V.rows()), -1);
  Mesh holed{Vertices(0, 3), Faces(static_cast<Eigen::Index>(kept.size()), 3)};
  int used = 0;
  for (std::size_t k = 0; k < kept.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      int& slot = index[static_cast<std::size_t>(mesh.F(kept[k], c))];
      if (slot < 0) slot = used++;
      holed.F(static_cast<Eigen::Index>(k), c) = slot;
    }
  holed.V.resize(used, 3);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (index[static_cast<std::size_t>(v)] >= 0) holed.V.row(index[static_cast<std::size_t>(v)]) = mesh.V.row(v);
  return holed;
}

Mesh pinched() {
  const Mesh a = creature(3);
  Eigen::Index tip_a = 0, tip_b = 0;
  a.V.col(0).maxCoeff(&tip_a);
  a.V.col(0).minCoeff(&tip_b);
  // b: a copy moved so that its leftmost vertex lands on a's rightmost one, then merged into it.
  Mesh both{Vertices(2 * a.V.rows() - 1, 3), Faces(2 * a.F.rows(), 3)};
  const Eigen::RowVector3d shift = a.V.row(tip_a) - a.V.row(tip_b);
  const auto b_index = [&](int v) {
    if (v == tip_b) return static_cast<int>(tip_a);
    return static_cast<int>(a.V.rows()) + (v < tip_b ? v : v - 1);
  };
  both.V.topRows(a.V.rows()) = a.V;
  for (Eigen::Index v = 0; v < a.V.rows(); ++v)
    if (v != tip_b) both.V.row(b_index(static_cast<int>(v))) = a.V.row(v) + shift;
  both.F.topRows(a.F.rows()) = a.F;
  for (Eigen::Index f = 0; f < a.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) both.F(a.F.rows() + f, c) = b_index(a.F(f, c));
  return both;
}

Mesh wound_inward(const Mesh& mesh) {
  Mesh inward = mesh;
  inward.F.col(1).swap(inward.F.col(2));
  return inward;
}

Mesh double_sided(const Mesh& mesh) {
  Mesh both{mesh.V, Faces(2 * mesh.F.rows(), 3)};
  both.F << mesh.F, wound_inward(mesh).F;
  return both;
}

Mesh example_shape(const std::string& name) {
  if (name == "creature") return creature(4);
  if (name == "creature-large") return creature(5);
  if (name == "torus") return lumpy_torus(96, 40, 1);
  if (name == "creature-holes") return with_holes(creature(5), 3, 0.15);
  if (name == "parts") return side_by_side(creature(4), lumpy_torus(64, 24, 1), 4.0);
  throw std::invalid_argument("no example shape named '" + name + "' (" + example_shape_names() + ")");
}

std::string example_shape_names() { return "creature, creature-large, torus, creature-holes, parts"; }

}  // namespace meshmark
