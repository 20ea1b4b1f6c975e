#include "tests/test_data.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>
#include <stdexcept>

#include "core/io/read_mesh.hpp"

namespace meshmark::test {

std::filesystem::path shared_mesh(const std::string& name) {
  const char* env = std::getenv("MESHMARK_MESHES");
  const std::filesystem::path dir = env ? env : MESHMARK_SHARED_MESHES;
  const auto path = dir / name;
  if (!std::filesystem::exists(path))
    throw std::runtime_error("shared test mesh not found: " + path.string() +
                             " (set MESHMARK_MESHES to the folder holding the shared meshes)");
  return path;
}

std::filesystem::path shared_asset(const std::string& relative) {
  const char* env = std::getenv("MESHMARK_ASSETS");
  const std::filesystem::path dir = env ? std::filesystem::path(env) : std::filesystem::path(MESHMARK_SHARED_MESHES) / ".." / "assets";
  const auto path = dir / relative;
  if (!std::filesystem::exists(path))
    throw std::runtime_error("shared test asset not found: " + path.string() +
                             " (set MESHMARK_ASSETS to the folder holding the shared assets)");
  return path;
}

const Mesh& load_shared(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, Mesh> cache;
  std::lock_guard lock(mutex);
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, read_mesh(shared_mesh(name)).mesh).first;
  return it->second;
}

Mesh icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
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

Mesh spot_with_holes() {
  const Mesh& spot = load_shared("spot.obj");
  Mesh holed{spot.V, Faces(spot.F.rows() - 3, 3)};
  Eigen::Index row = 0;
  for (Eigen::Index f = 0; f < spot.F.rows(); ++f)
    if (f != 100 && f != 2000 && f != 4000) holed.F.row(row++) = spot.F.row(f);
  return holed;
}

Mesh side_by_side(const Mesh& a, const Mesh& b, double shift) {
  Mesh both;
  both.V.resize(a.V.rows() + b.V.rows(), 3);
  both.V << a.V, (b.V.array() + shift).matrix();
  both.F.resize(a.F.rows() + b.F.rows(), 3);
  both.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return both;
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

Mesh torus(int rings, int segments) {
  Mesh mesh;
  mesh.V.resize(rings * segments, 3);
  mesh.F.resize(2 * rings * segments, 3);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double u = 2 * M_PI * i / rings, w = 2 * M_PI * j / segments;
      mesh.V.row(i * segments + j) << (2 + std::cos(w)) * std::cos(u), (2 + std::cos(w)) * std::sin(u), std::sin(w);
      const int a = i * segments + j, b = ((i + 1) % rings) * segments + j, c = ((i + 1) % rings) * segments + (j + 1) % segments,
                d = i * segments + (j + 1) % segments;
      mesh.F.row(2 * a) << a, b, c;
      mesh.F.row(2 * a + 1) << a, c, d;
    }
  return mesh;
}

}  // namespace meshmark::test
