#include "core/mesh/cut_to_manifold.hpp"

#include <numeric>

#include "core/mesh/edge_incidence.hpp"
#include "core/util/union_find.hpp"

namespace meshmark {

ManifoldPieces cut_to_manifold(const Mesh& mesh) {
  ManifoldPieces out;
  // The faces kept: those with three distinct corners.
  std::vector<Eigen::Index> kept;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    if (a != b && b != c && a != c) kept.push_back(f);
  }
  out.dropped_faces = static_cast<std::size_t>(mesh.F.rows()) - kept.size();
  Faces F(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) F.row(static_cast<Eigen::Index>(i)) = mesh.F.row(kept[i]);

  // Corners (f, k) are 3f + k. Across a joinable edge, the corners at each end are one fan.
  const EdgeIncidence inc = edge_incidence(F);
  std::vector<int> first(static_cast<std::size_t>(inc.edges.rows()), -1), second(first.size(), -1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto e = static_cast<std::size_t>(inc.face_edges(f, k));
      (first[e] < 0 ? first[e] : second[e]) = static_cast<int>(3 * f + k);  // the corner the edge starts at
    }
  UnionFind fans(static_cast<std::size_t>(3 * F.rows()));
  for (std::size_t e = 0; e < first.size(); ++e) {
    if (inc.face_count[e] != 2 || inc.along_count[e] != 1) continue;
    // Corner c starts its face's edge e; (c+1 within the face) ends it. Opposite windings: the
    // start of one is the end of the other.
    const auto next = [](int c) { return 3 * (c / 3) + (c % 3 + 1) % 3; };
    fans.unite(first[e], next(second[e]));
    fans.unite(next(first[e]), second[e]);
  }

  // The first fan of each vertex keeps it; every other fan gets a copy.
  out.mesh.F = F;
  out.origin.resize(static_cast<std::size_t>(mesh.V.rows()));
  std::iota(out.origin.begin(), out.origin.end(), 0);
  std::vector<int> fan_vertex(static_cast<std::size_t>(3 * F.rows()), -1);  // per fan root
  std::vector<int> owner(static_cast<std::size_t>(mesh.V.rows()), -1);      // the fan root that kept the vertex
  for (int c = 0; c < 3 * static_cast<int>(F.rows()); ++c) {
    const int v = F(c / 3, c % 3), root = fans.find(c);
    auto& assigned = fan_vertex[static_cast<std::size_t>(root)];
    if (assigned < 0) {
      if (owner[static_cast<std::size_t>(v)] < 0) {
        owner[static_cast<std::size_t>(v)] = root;
        assigned = v;
      } else {
        assigned = static_cast<int>(out.origin.size());
        out.origin.push_back(v);
      }
    }
    out.mesh.F(c / 3, c % 3) = assigned;
  }
  out.mesh.V.resize(static_cast<Eigen::Index>(out.origin.size()), 3);
  for (std::size_t v = 0; v < out.origin.size(); ++v)
    out.mesh.V.row(static_cast<Eigen::Index>(v)) = mesh.V.row(out.origin[v]);
  return out;
}

}  // namespace meshmark
