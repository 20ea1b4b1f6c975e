#include "core/mesh/vertex_neighbors.hpp"

#include "core/mesh/edge_incidence.hpp"

namespace meshmark {

VertexNeighbors vertex_neighbors(const Faces& F, Eigen::Index vertex_count) {
  const EdgeIncidence inc = edge_incidence(F);
  VertexNeighbors result;
  result.offsets.assign(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (Eigen::Index e = 0; e < inc.edges.rows(); ++e) {
    ++result.offsets[inc.edges(e, 0) + 1];
    ++result.offsets[inc.edges(e, 1) + 1];
  }
  for (std::size_t v = 1; v < result.offsets.size(); ++v) result.offsets[v] += result.offsets[v - 1];
  result.neighbors.resize(static_cast<std::size_t>(result.offsets.back()));
  std::vector<int> cursor(result.offsets.begin(), result.offsets.end() - 1);
  // Edges are sorted, so each row fills in ascending order of the other end... for the smaller
  // end; the larger end's row gets its smaller neighbours first, also ascending.
  for (Eigen::Index e = 0; e < inc.edges.rows(); ++e) {
    const int a = inc.edges(e, 0), b = inc.edges(e, 1);
    result.neighbors[cursor[a]++] = b;
    result.neighbors[cursor[b]++] = a;
  }
  return result;
}

}  // namespace meshmark
