#include "core/metrics/compare_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/mesh/massmatrix.hpp"
#include "core/spatial/aabb_tree.hpp"
#include "core/spatial/morton_order.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

SurfaceSampler::SurfaceSampler(const Mesh& mesh) : mesh_(mesh) {
  const Eigen::VectorXd area = face_areas(mesh.V, mesh.F);
  cumulative_.resize(static_cast<std::size_t>(area.size()));
  double total = 0;
  for (Eigen::Index f = 0; f < area.size(); ++f) cumulative_[static_cast<std::size_t>(f)] = total += area[f];
}

Vertices SurfaceSampler::sample(std::size_t n, std::vector<int>* faces) const {
  const double total = cumulative_.empty() ? 0.0 : cumulative_.back();
  Vertices P(static_cast<Eigen::Index>(n), 3);
  if (faces) faces->resize(n);
  // Stratified in the face choice, R2 low-discrepancy sequence within the triangle.
  const double g = 1.32471795724474602596, a1 = 1.0 / g, a2 = 1.0 / (g * g);
  // The targets grow with i, so the first face whose cumulative area reaches each one (a binary
  // search per sample before, cache misses at millions of faces) is found by walking forward.
  std::size_t face = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double target = (static_cast<double>(i) + 0.5) / static_cast<double>(n) * total;
    while (face < cumulative_.size() && cumulative_[face] < target) ++face;
    const auto f = static_cast<Eigen::Index>(std::min(face, cumulative_.size() - 1));
    double r1 = std::fmod(0.5 + a1 * static_cast<double>(i), 1.0),
           r2 = std::fmod(0.5 + a2 * static_cast<double>(i), 1.0);
    if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;  // fold the square onto the triangle
    if (faces) (*faces)[i] = static_cast<int>(f);
    P.row(static_cast<Eigen::Index>(i)) =
        (1 - r1 - r2) * mesh_.V.row(mesh_.F(f, 0)) + r1 * mesh_.V.row(mesh_.F(f, 1)) + r2 * mesh_.V.row(mesh_.F(f, 2));
  }
  return P;
}

Vertices sample_surface(const Mesh& mesh, std::size_t n, std::vector<int>* faces) {
  return SurfaceSampler(mesh).sample(n, faces);
}

namespace {

// Squared distances from `points` to the tree's surface, in parallel; each point writes its own
// entry, so the sums made of them do not depend on the thread count.
std::vector<double> squared_distances(const AabbTree& tree, const Vertices& points, int threads) {
  std::vector<double> d2(static_cast<std::size_t>(points.rows()));
  const std::vector<std::int64_t> order = morton_order(points);
  parallel_for(points.rows(), threads, [&](std::int64_t begin, std::int64_t end) {
    int hint = -1;  // the last point's face: in Z-order, the next point is near
    for (std::int64_t n = begin; n < end; ++n) {
      const std::int64_t i = order[static_cast<std::size_t>(n)];
      const TriangleHit hit =
          *tree.closest_point(points.row(i).transpose(), std::numeric_limits<double>::infinity(), hint);
      d2[static_cast<std::size_t>(i)] = hit.distance_squared;
      hint = hit.face;
    }
  });
  return d2;
}

// The rows of A's vertices whose distance to B's surface could exceed sqrt(max2). When A and B
// share their faces (a marked copy and its original), B's vertex i lies on B's surface wherever a
// face uses it, so |a_i − b_i| bounds A's vertex i: the few that moved most are queried, not all
// (at 2.2M vertices, most of the distortion line's time). The margin keeps a rounding of the
// query from ever exceeding a bound that skipped it: the max is the one all queries give.
Vertices vertices_above(const Mesh& a, const Mesh& b, double max2) {
  if (!same_connectivity(a, b)) return a.V;
  std::vector<char> on_surface(static_cast<std::size_t>(a.V.rows()), 0);
  for (Eigen::Index f = 0; f < a.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) on_surface[static_cast<std::size_t>(a.F(f, k))] = 1;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < a.V.rows(); ++i)
    if (!on_surface[static_cast<std::size_t>(i)] || !((a.V.row(i) - b.V.row(i)).squaredNorm() < max2 * (1 - 1e-9)))
      kept.push_back(i);
  Vertices rows(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t k = 0; k < kept.size(); ++k) rows.row(static_cast<Eigen::Index>(k)) = a.V.row(kept[k]);
  return rows;
}

// RMS and max distance from A's samples and vertices to B's surface.
void one_side(const Mesh& a, const Mesh& b, const CompareOptions& options, double& rms, double& max) {
  const AabbTree tree(b.V, b.F);
  const std::vector<double> samples = squared_distances(tree, sample_surface(a, options.samples), options.threads);
  double sum = 0, max2 = 0;
  for (const double d2 : samples) sum += d2, max2 = std::max(max2, d2);
  for (const double d2 : squared_distances(tree, vertices_above(a, b, max2), options.threads))
    max2 = std::max(max2, d2);
  max = std::sqrt(max2);
  rms = std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, samples.size())));
}

}  // namespace

SurfaceDistance compare_meshes(const Mesh& a, const Mesh& b, const CompareOptions& options) {
  SurfaceDistance d;
  d.diagonal = (a.V.colwise().maxCoeff() - a.V.colwise().minCoeff()).norm();
  one_side(a, b, options, d.rms_ab, d.max_ab);
  one_side(b, a, options, d.rms_ba, d.max_ba);
  d.mrms = std::max(d.rms_ab, d.rms_ba);
  d.hausdorff = std::max(d.max_ab, d.max_ba);
  return d;
}

}  // namespace meshmark
