#include "core/param/repair_spherical_flips.hpp"

#include <algorithm>
#include <vector>

#include "core/mesh/vertex_neighbors.hpp"
#include "core/param/check_spherical_map.hpp"

namespace meshmark {

namespace {

// Vertices of the flipped faces, grown by `rings` rings, ascending.
std::vector<int> region_around(const std::vector<int>& flipped, const Faces& F, const VertexNeighbors& nb, int rings,
                               std::vector<char>& in_region) {
  std::fill(in_region.begin(), in_region.end(), 0);
  std::vector<int> region;
  for (int f : flipped)
    for (int k = 0; k < 3; ++k)
      if (!in_region[F(f, k)]) in_region[F(f, k)] = 1, region.push_back(F(f, k));
  std::size_t frontier = 0;
  for (int r = 0; r < rings; ++r) {
    const std::size_t end = region.size();
    for (std::size_t i = frontier; i < end; ++i)
      for (int j = nb.offsets[region[i]]; j < nb.offsets[region[i] + 1]; ++j)
        if (!in_region[nb.neighbors[j]]) in_region[nb.neighbors[j]] = 1, region.push_back(nb.neighbors[j]);
    frontier = end;
  }
  std::sort(region.begin(), region.end());
  return region;
}

}  // namespace

RepairResult repair_spherical_flips(Vertices& S, const Faces& F, const RepairOptions& options) {
  RepairResult result;
  const VertexNeighbors nb = vertex_neighbors(F, S.rows());
  std::vector<char> in_region(static_cast<std::size_t>(S.rows()), 0);
  for (; result.rounds <= options.max_rounds; ++result.rounds) {
    const SphericalMapCheck check = check_spherical_map(S, F);
    if (check.flipped_faces == 0) {
      result.success = true;
      return result;
    }
    if (result.rounds == options.max_rounds) break;
    const std::vector<int> region = region_around(check.flipped, F, nb, result.rounds + 1, in_region);
    result.relaxed_vertices = region.size();
    for (int sweep = 0; sweep < options.sweeps_per_round; ++sweep)
      for (int v : region) {
        Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
        for (int j = nb.offsets[v]; j < nb.offsets[v + 1]; ++j) sum += S.row(nb.neighbors[j]);
        if (sum.norm() > 0) S.row(v) = sum.normalized();
      }
  }
  return result;
}

}  // namespace meshmark
