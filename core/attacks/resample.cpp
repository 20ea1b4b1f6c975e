#include "core/attacks/resample.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "core/mesh/edge_incidence.hpp"
#include "core/mesh/vertex_normals.hpp"
#include "core/spatial/aabb_tree.hpp"
#include "core/spatial/winding_number.hpp"

namespace meshmark {

namespace {

constexpr double kMaxGridPoints = 64e6;

struct Grid {
  Eigen::Vector3d origin;
  double step = 0;
  std::array<long, 3> size{};  // points along each axis
  long index(long i, long j, long k) const { return (k * size[1] + j) * size[0] + i; }
  long count() const { return size[0] * size[1] * size[2]; }
  Eigen::Vector3d point(long i, long j, long k) const {
    return origin + step * Eigen::Vector3d(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
  }
};

Grid make_grid(const Mesh& mesh, double spacing) {
  const Eigen::Vector3d low = mesh.V.colwise().minCoeff(), high = mesh.V.colwise().maxCoeff();
  Grid grid;
  grid.step = spacing * (high - low).norm();
  grid.origin = low - 2 * grid.step * Eigen::Vector3d::Ones();  // a border of outside points
  double points = 1;
  for (int a = 0; a < 3; ++a) {
    grid.size[a] = static_cast<long>(std::ceil((high[a] - low[a]) / grid.step)) + 5;
    points *= static_cast<double>(grid.size[a]);
  }
  if (points > kMaxGridPoints)
    throw std::invalid_argument("resampling at this spacing needs a grid of " + std::to_string(points / 1e6) +
                                " million points, more than 64 million: give a larger spacing");
  return grid;
}

// The sign of the distance at a closest point: which side of the angle-weighted pseudo-normal of
// the feature (face, edge or vertex) the closest point lies on (Bærentzen and Aanæs 2005).
class PseudoNormals {
 public:
  PseudoNormals(const Mesh& mesh, const EdgeIncidence& incidence)
      : F_(mesh.F), face_(face_normals(mesh.V, mesh.F)), incidence_(incidence) {
    edge_ = Vertices::Zero(incidence_.edges.rows(), 3);
    vertex_ = Vertices::Zero(mesh.V.rows(), 3);
    for (Eigen::Index f = 0; f < F_.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        edge_.row(incidence_.face_edges(f, k)) += face_.row(f);
        const Eigen::Vector3d a = mesh.V.row(F_(f, k)), b = mesh.V.row(F_(f, (k + 1) % 3)),
                              c = mesh.V.row(F_(f, (k + 2) % 3));
        const double angle = std::acos(std::clamp((b - a).normalized().dot((c - a).normalized()), -1.0, 1.0));
        vertex_.row(F_(f, k)) += angle * face_.row(f);
      }
  }

  Eigen::Vector3d at(const TriangleHit& hit) const {
    constexpr double kOnFeature = 1e-9;
    int zeros = 0, last_zero = 0, nonzero = 0;
    for (int k = 0; k < 3; ++k)
      if (hit.bary[k] < kOnFeature) ++zeros, last_zero = k;
      else nonzero = k;
    if (zeros == 2) return vertex_.row(F_(hit.face, nonzero));
    if (zeros == 1) return edge_.row(incidence_.face_edges(hit.face, (last_zero + 1) % 3));
    return face_.row(hit.face);
  }

 private:
  const Faces& F_;
  Vertices face_, edge_, vertex_;
  const EdgeIncidence& incidence_;
};

// Distances at the grid points within two steps of a triangle's bounding box, elsewhere NaN;
// signed by the pseudo-normals when given (a closed surface), else unsigned.
std::vector<float> narrow_band(const Mesh& mesh, const Grid& grid, const PseudoNormals* normals) {
  std::vector<float> value(static_cast<std::size_t>(grid.count()), std::nanf(""));
  const AabbTree tree(mesh.V, mesh.F);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    Eigen::AlignedBox3d box;
    for (int k = 0; k < 3; ++k) box.extend(Eigen::Vector3d(mesh.V.row(mesh.F(f, k)).transpose()));
    std::array<long, 3> from{}, to{};
    for (int a = 0; a < 3; ++a) {
      from[a] = std::max(0L, static_cast<long>(std::floor((box.min()[a] - grid.origin[a]) / grid.step)) - 2);
      to[a] = std::min(grid.size[a] - 1, static_cast<long>(std::ceil((box.max()[a] - grid.origin[a]) / grid.step)) + 2);
    }
    for (long k = from[2]; k <= to[2]; ++k)
      for (long j = from[1]; j <= to[1]; ++j)
        for (long i = from[0]; i <= to[0]; ++i) {
          float& v = value[static_cast<std::size_t>(grid.index(i, j, k))];
          if (!std::isnan(v)) continue;
          const Eigen::Vector3d p = grid.point(i, j, k);
          const TriangleHit hit = *tree.closest_point(p);
          const double distance = std::sqrt(hit.distance_squared);
          v = static_cast<float>(!normals || normals->at(hit).dot(p - hit.point) >= 0 ? distance : -distance);
          if (v == 0) v = 1e-30f;  // no vertex exactly on the level set
        }
  }
  return value;
}

// Points outside the band: outside (+) when a flood fill from the grid's border reaches them
// without crossing the band, else inside (−).
void sign_far_points(std::vector<float>& value, const Grid& grid) {
  std::vector<char> outside(value.size(), 0);
  std::vector<long> stack;
  const auto push = [&](long i, long j, long k) {
    const long n = grid.index(i, j, k);
    if (outside[static_cast<std::size_t>(n)] || !std::isnan(value[static_cast<std::size_t>(n)])) return;
    outside[static_cast<std::size_t>(n)] = 1;
    stack.push_back(n);
  };
  push(0, 0, 0);  // a corner: two steps clear of any triangle
  while (!stack.empty()) {
    const long n = stack.back();
    stack.pop_back();
    const long i = n % grid.size[0], j = (n / grid.size[0]) % grid.size[1], k = n / (grid.size[0] * grid.size[1]);
    if (i > 0) push(i - 1, j, k);
    if (i + 1 < grid.size[0]) push(i + 1, j, k);
    if (j > 0) push(i, j - 1, k);
    if (j + 1 < grid.size[1]) push(i, j + 1, k);
    if (k > 0) push(i, j, k - 1);
    if (k + 1 < grid.size[2]) push(i, j, k + 1);
  }
  const float far = static_cast<float>(3 * grid.step);
  for (std::size_t n = 0; n < value.size(); ++n)
    if (std::isnan(value[n])) value[n] = outside[n] ? far : -far;
}

// A surface with holes has no inside a flood fill could find, and near a hole the pseudo-normal's
// sign flips across a sheet grown out of the border. There every point takes its side from the
// generalized winding number (inside where it is at least 1/2), which closes each hole with a
// smooth cap, as libigl's signed distance does; the magnitudes stay the distances.
void sign_by_winding_number(const Mesh& mesh, const Grid& grid, std::vector<float>& value) {
  const WindingNumber winding(mesh.V, mesh.F);
  const float far = static_cast<float>(3 * grid.step);
  for (long k = 0; k < grid.size[2]; ++k)
    for (long j = 0; j < grid.size[1]; ++j)
      for (long i = 0; i < grid.size[0]; ++i) {
        float& v = value[static_cast<std::size_t>(grid.index(i, j, k))];
        const float size = std::isnan(v) ? far : std::abs(v);
        v = winding.at(grid.point(i, j, k)) >= 0.5 ? -size : size;
      }
}

// Marching tetrahedra over every cube with a sign change; vertices on grid edges are shared.
class LevelSetExtractor {
 public:
  LevelSetExtractor(const std::vector<float>& value, const Grid& grid) : value_(value), grid_(grid) {}

  Mesh extract() {
    // The six tetrahedra of a cube around its main diagonal (corner 0 to corner 7).
    static constexpr std::array<std::array<int, 4>, 6> kTets = {
        {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}}};
    for (long k = 0; k + 1 < grid_.size[2]; ++k)
      for (long j = 0; j + 1 < grid_.size[1]; ++j)
        for (long i = 0; i + 1 < grid_.size[0]; ++i) {
          std::array<long, 8> corner{};
          bool positive = false, negative = false;
          for (int c = 0; c < 8; ++c) {
            corner[c] = grid_.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
            (value_[static_cast<std::size_t>(corner[c])] > 0 ? positive : negative) = true;
          }
          if (!(positive && negative)) continue;
          for (const auto& tet : kTets) march({corner[tet[0]], corner[tet[1]], corner[tet[2]], corner[tet[3]]});
        }
    Mesh out;
    out.V.resize(static_cast<Eigen::Index>(points_.size()), 3);
    for (std::size_t v = 0; v < points_.size(); ++v) out.V.row(static_cast<Eigen::Index>(v)) = points_[v];
    out.F.resize(static_cast<Eigen::Index>(faces_.size()), 3);
    for (std::size_t f = 0; f < faces_.size(); ++f)
      out.F.row(static_cast<Eigen::Index>(f)) << faces_[f][0], faces_[f][1], faces_[f][2];
    return out;
  }

 private:
  Eigen::Vector3d position(long n) const {
    return grid_.point(n % grid_.size[0], (n / grid_.size[0]) % grid_.size[1], n / (grid_.size[0] * grid_.size[1]));
  }

  // The level set's vertex on grid edge (a, b), made once.
  int crossing(long a, long b) {
    if (a > b) std::swap(a, b);
    const auto key = static_cast<unsigned long long>(a) * static_cast<unsigned long long>(grid_.count()) +
                     static_cast<unsigned long long>(b);
    const auto [it, made] = vertex_of_edge_.try_emplace(key, static_cast<int>(points_.size()));
    if (made) {
      const double fa = value_[static_cast<std::size_t>(a)], fb = value_[static_cast<std::size_t>(b)];
      const double t = fa / (fa - fb);
      points_.push_back(((1 - t) * position(a) + t * position(b)).transpose());
    }
    return it->second;
  }

  void emit(int a, int b, int c, const Eigen::Vector3d& outward) {
    if (a == b || b == c || c == a) return;
    const Eigen::Vector3d pa = points_[a], pb = points_[b], pc = points_[c];
    if ((pb - pa).cross(pc - pa).dot(outward) < 0) std::swap(b, c);
    faces_.push_back({a, b, c});
  }

  void march(const std::array<long, 4>& tet) {
    std::vector<long> inside, outside;
    Eigen::Vector3d in_centre = Eigen::Vector3d::Zero(), out_centre = Eigen::Vector3d::Zero();
    for (const long n : tet)
      if (value_[static_cast<std::size_t>(n)] > 0) outside.push_back(n), out_centre += position(n);
      else inside.push_back(n), in_centre += position(n);
    if (inside.empty() || outside.empty()) return;
    const Eigen::Vector3d outward =
        out_centre / static_cast<double>(outside.size()) - in_centre / static_cast<double>(inside.size());
    if (inside.size() == 2) {  // a quad: two triangles
      const int a = crossing(inside[0], outside[0]), b = crossing(inside[0], outside[1]),
                c = crossing(inside[1], outside[1]), d = crossing(inside[1], outside[0]);
      emit(a, b, c, outward);
      emit(a, c, d, outward);
      return;
    }
    const std::vector<long>& one = inside.size() == 1 ? inside : outside;
    const std::vector<long>& three = inside.size() == 1 ? outside : inside;
    emit(crossing(one[0], three[0]), crossing(one[0], three[1]), crossing(one[0], three[2]), outward);
  }

  const std::vector<float>& value_;
  const Grid& grid_;
  std::unordered_map<unsigned long long, int> vertex_of_edge_;
  std::vector<Eigen::RowVector3d> points_;
  std::vector<std::array<int, 3>> faces_;
};

}  // namespace

Mesh resample_surface(const Mesh& mesh, double spacing) {
  if (!(spacing >= 0.001 && spacing <= 0.1))
    throw std::invalid_argument("the resampling spacing must be between 0.001 and 0.1 of the diagonal");
  if (mesh.F.rows() == 0) throw std::invalid_argument("resampling needs a surface with faces");
  const Grid grid = make_grid(mesh, spacing);
  const EdgeIncidence incidence = edge_incidence(mesh.F);
  const auto& uses = incidence.face_count;
  std::vector<float> value;
  if (std::find(uses.begin(), uses.end(), 1) != uses.end()) {  // a boundary: no inside to flood
    value = narrow_band(mesh, grid, nullptr);
    sign_by_winding_number(mesh, grid, value);
  } else {
    const PseudoNormals normals(mesh, incidence);
    value = narrow_band(mesh, grid, &normals);
    sign_far_points(value, grid);
  }
  return LevelSetExtractor(value, grid).extract();
}

}  // namespace meshmark
