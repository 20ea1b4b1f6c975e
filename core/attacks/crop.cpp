#include "core/attacks/crop.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/mesh/massmatrix.hpp"
#include "core/util/keyed_random.hpp"

namespace meshmark {

Mesh keep_faces(const Mesh& mesh, const std::vector<int>& faces) {
  std::vector<int> index(static_cast<std::size_t>(mesh.V.rows()), -1);
  for (int f : faces)
    for (int k = 0; k < 3; ++k) index[mesh.F(f, k)] = 0;
  int next = 0;
  for (int& i : index)
    if (i == 0) i = next++;
  Mesh out;
  out.V.resize(next, 3);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (index[v] >= 0) out.V.row(index[v]) = mesh.V.row(v);
  out.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 3; ++k) out.F(static_cast<Eigen::Index>(i), k) = index[mesh.F(faces[i], k)];
  return out;
}

Mesh crop(const Mesh& mesh, double fraction, std::uint64_t seed) {
  if (!(fraction >= 0 && fraction < 1)) throw std::invalid_argument("the cropped fraction must be in [0, 1)");
  KeyedRandom random("attack", "crop/" + std::to_string(seed));
  // A uniformly random direction (normalized Gaussian via Box–Muller).
  Eigen::Vector3d d;
  for (int k = 0; k < 3; ++k)
    d[k] = std::sqrt(-2 * std::log(random.unit() + 1e-300)) * std::cos(2 * M_PI * random.unit());
  d.normalize();
  const Eigen::VectorXd area = face_areas(mesh.V, mesh.F);
  std::vector<int> order(static_cast<std::size_t>(mesh.F.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> height(order.size());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    height[f] = (mesh.V.row(mesh.F(f, 0)) + mesh.V.row(mesh.F(f, 1)) + mesh.V.row(mesh.F(f, 2))).dot(d.transpose()) / 3;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return height[a] != height[b] ? height[a] > height[b] : a < b; });
  // Remove from the far side of the plane until the area is gone.
  const double target = fraction * area.sum();
  double removed = 0;
  std::size_t cut = 0;
  while (cut < order.size() && removed + 0.5 * area[order[cut]] < target) removed += area[order[cut++]];
  std::vector<int> kept(order.begin() + static_cast<long>(cut), order.end());
  std::sort(kept.begin(), kept.end());
  return keep_faces(mesh, kept);
}

}  // namespace meshmark
