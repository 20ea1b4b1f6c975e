#include "core/watermark/measure_by_projection.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/metrics/compare_meshes.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/spatial/morton_order.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

// The suspect's faces in Z-order of their centroids, each with its samples (sample_surface makes
// them face by face): queries in this order find the tree's nodes and the last hit's face near,
// where in the file's order (a shuffled copy) they waited on memory at millions of vertices.
std::vector<std::uint32_t> samples_in_face_z_order(const Mesh& suspect, const std::vector<int>& sample_face) {
  std::vector<std::int64_t> faces;
  {
    Vertices centroids(suspect.F.rows(), 3);
    for (Eigen::Index f = 0; f < suspect.F.rows(); ++f)
      centroids.row(f) =
          (suspect.V.row(suspect.F(f, 0)) + suspect.V.row(suspect.F(f, 1)) + suspect.V.row(suspect.F(f, 2))) / 3;
    faces = morton_order(centroids);
  }
  std::vector<std::uint32_t> first(static_cast<std::size_t>(suspect.F.rows()) + 1, 0);
  for (const int f : sample_face) ++first[static_cast<std::size_t>(f) + 1];
  for (std::size_t f = 1; f < first.size(); ++f) first[f] += first[f - 1];
  std::vector<std::uint32_t> order;
  order.reserve(sample_face.size());
  for (const std::int64_t f : faces)
    for (std::uint32_t i = first[static_cast<std::size_t>(f)]; i < first[static_cast<std::size_t>(f) + 1]; ++i)
      order.push_back(i);
  return order;
}

}  // namespace

Displacement measure_by_projection(const AabbTree& original_tree, const Mesh& original, const Vertices& face_normals,
                                   const Mesh& suspect, double diagonal, const DisplacementOptions& options,
                                   int threads) {
  const double radius = options.search_radius * diagonal;
  const auto n = static_cast<std::size_t>(options.samples_per_vertex * static_cast<double>(original.V.rows()));
  // Sample numbers as 32 bits: at most 6 per vertex of an original the readers accept (50 million).
  if (n > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("too many samples to project: " + std::to_string(n));
  std::vector<int> sample_face;
  const Vertices samples = sample_surface(suspect, n, &sample_face);
  const std::vector<std::uint32_t> order = samples_in_face_z_order(suspect, sample_face);
  sample_face = {};
  Eigen::VectorXd height = Eigen::VectorXd::Zero(original.V.rows()), weight = Eigen::VectorXd::Zero(original.V.rows());
  // The queries in parallel, a block at a time (a hit is 80 bytes: all of them at once were a
  // quarter of a 557k-vertex detection's memory); the sums in that order, so the result does not
  // depend on the thread count.
  constexpr std::int64_t kBlock = 1 << 16;
  const auto total = static_cast<std::int64_t>(order.size());
  std::vector<std::optional<TriangleHit>> hits(static_cast<std::size_t>(std::min(kBlock, total)));
  for (std::int64_t first = 0; first < total; first += kBlock) {
    const std::int64_t count = std::min(kBlock, total - first);
    parallel_for(count, threads, [&](std::int64_t begin, std::int64_t end) {
      int hint = -1;  // the last hit's face: the next sample is near
      for (std::int64_t k = begin; k < end; ++k) {
        hits[k] = original_tree.closest_point(samples.row(order[first + k]).transpose(), radius, hint);
        hint = hits[k] ? hits[k]->face : -1;
      }
    });
    for (std::int64_t k = 0; k < count; ++k) {
      const auto& hit = hits[k];
      if (!hit) continue;  // a piece of the suspect far from the original: no evidence
      const double h =
          (samples.row(order[first + k]).transpose() - hit->point).dot(face_normals.row(hit->face).transpose());
      for (int c = 0; c < 3; ++c) {
        const int v = original.F(hit->face, c);
        height[v] += hit->bary[c] * h;
        weight[v] += hit->bary[c];
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
