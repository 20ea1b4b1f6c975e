#include "core/watermark/measure_by_projection.hpp"

#include <algorithm>
#include <optional>
#include <vector>

#include "core/metrics/compare_meshes.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

Displacement measure_by_projection(const AabbTree& original_tree, const Mesh& original, const Vertices& face_normals,
                                   const Mesh& suspect, double diagonal, const DisplacementOptions& options,
                                   int threads) {
  const double radius = options.search_radius * diagonal;
  const auto n = static_cast<std::size_t>(options.samples_per_vertex * static_cast<double>(original.V.rows()));
  const Vertices samples = sample_surface(suspect, n);
  Eigen::VectorXd height = Eigen::VectorXd::Zero(original.V.rows()), weight = Eigen::VectorXd::Zero(original.V.rows());
  // The queries in parallel, a block at a time (a hit is 80 bytes: all of them at once were a
  // quarter of a 557k-vertex detection's memory); the sums in sample order, so the result does not
  // depend on the thread count.
  constexpr Eigen::Index kBlock = 1 << 16;
  std::vector<std::optional<TriangleHit>> hits(static_cast<std::size_t>(std::min(kBlock, samples.rows())));
  for (Eigen::Index first = 0; first < samples.rows(); first += kBlock) {
    const Eigen::Index count = std::min(kBlock, samples.rows() - first);
    parallel_for(count, threads, [&](std::int64_t begin, std::int64_t end) {
      int hint = -1;  // samples come face by face along the suspect: the last hit's face is near
      for (std::int64_t i = begin; i < end; ++i) {
        hits[i] = original_tree.closest_point(samples.row(first + i).transpose(), radius, hint);
        hint = hits[i] ? hits[i]->face : -1;
      }
    });
    for (Eigen::Index i = 0; i < count; ++i) {
      const auto& hit = hits[i];
      if (!hit) continue;  // a piece of the suspect far from the original: no evidence
      const double h = (samples.row(first + i).transpose() - hit->point).dot(face_normals.row(hit->face).transpose());
      for (int k = 0; k < 3; ++k) {
        const int v = original.F(hit->face, k);
        height[v] += hit->bary[k] * h;
        weight[v] += hit->bary[k];
      }
    }
  }
  // A vertex counts as read when at least a fifth of its expected share of samples arrived: its
  // share of the original's area times the samples taken (uniform by area).
  const Eigen::VectorXd area = vertex_areas(original.V, original.F);
  const double per_area = static_cast<double>(n) / area.sum();
  Displacement d;
  d.t = Eigen::VectorXd::Zero(original.V.rows());
  d.found.assign(static_cast<std::size_t>(original.V.rows()), 0);
  for (Eigen::Index v = 0; v < original.V.rows(); ++v) {
    if (weight[v] > 0 && weight[v] >= options.min_share * per_area * area[v]) {
      d.t[v] = height[v] / weight[v];
      d.found[v] = 1;
    } else {
      ++d.missing;
    }
  }
  return d;
}

}  // namespace meshmark
