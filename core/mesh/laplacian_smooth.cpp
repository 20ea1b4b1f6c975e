#include "core/mesh/laplacian_smooth.hpp"

#include <stdexcept>

#include "core/util/parallel_for.hpp"

namespace meshmark {

Mesh laplacian_smooth(const Mesh& mesh, double lambda, int iterations, int threads) {
  return {laplacian_smooth(mesh.V, vertex_neighbors(mesh.F, mesh.V.rows()), lambda, iterations, threads), mesh.F};
}

Vertices laplacian_smooth(const Vertices& V, const VertexNeighbors& nb, double lambda, int iterations, int threads) {
  if (iterations < 0) throw std::invalid_argument("smoothing iterations must not be negative");
  Vertices out = V, next(V.rows(), 3);
  for (int it = 0; it < iterations; ++it) {
    parallel_for(out.rows(), threads, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t v = first; v < last; ++v) {
        const int begin = nb.offsets[v], end = nb.offsets[v + 1];
        if (begin == end) {
          next.row(v) = out.row(v);
          continue;
        }
        Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
        for (int j = begin; j < end; ++j) mean += out.row(nb.neighbors[j]);
        mean /= static_cast<double>(end - begin);
        next.row(v) = out.row(v) + lambda * (mean - out.row(v));
      }
    });
    out.swap(next);
  }
  return out;
}

}  // namespace meshmark
