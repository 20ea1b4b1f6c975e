#include "core/basis/multiscale_bumps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <queue>
#include <unordered_map>

#include "core/util/parallel_for.hpp"
#include "core/util/union_find.hpp"

namespace meshmark {

namespace {

// Undirected edges in compressed rows with their lengths.
struct Graph {
  std::vector<int> offsets, neighbors;
  std::vector<double> lengths;
};

Graph edge_graph(const Mesh& mesh) {
  const auto n = static_cast<std::size_t>(mesh.V.rows());
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(6 * mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (a == b) continue;
      edges.emplace_back(a, b);
      edges.emplace_back(b, a);
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  Graph g;
  g.offsets.assign(n + 1, 0);
  for (const auto& e : edges) ++g.offsets[static_cast<std::size_t>(e.first) + 1];
  std::partial_sum(g.offsets.begin(), g.offsets.end(), g.offsets.begin());
  g.neighbors.reserve(edges.size());
  g.lengths.reserve(edges.size());
  for (const auto& [a, b] : edges) {
    g.neighbors.push_back(b);
    g.lengths.push_back((mesh.V.row(a) - mesh.V.row(b)).norm());
  }
  return g;
}

// A vertex's roughness: its distance from its neighbours' mean, in units of its mean edge.
std::vector<double> vertex_roughness(const Mesh& mesh, const Graph& g) {
  std::vector<double> r(static_cast<std::size_t>(mesh.V.rows()), 0.0);
  for (std::size_t v = 0; v + 1 < g.offsets.size(); ++v) {
    const int begin = g.offsets[v], end = g.offsets[v + 1];
    if (begin == end) continue;
    Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
    double edge = 0;
    for (int e = begin; e < end; ++e)
      mean += mesh.V.row(g.neighbors[static_cast<std::size_t>(e)]), edge += g.lengths[static_cast<std::size_t>(e)];
    mean /= end - begin;
    edge /= end - begin;
    if (edge > 0) r[v] = (mesh.V.row(static_cast<Eigen::Index>(v)) - mean).norm() / edge;
  }
  return r;
}

// Centres at least `spacing` apart (Euclidean), taken in a fixed scrambled vertex order: a
// maximal Poisson-disk set of the eligible vertices, the same for every run.
std::vector<int> spread_centres(const Mesh& mesh, const std::vector<int>& order, double spacing) {
  struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct CellHash {
    std::size_t operator()(const Cell& c) const {
      return static_cast<std::size_t>(c.x * 73856093 ^ c.y * 19349663 ^ c.z * 83492791);
    }
  };
  std::unordered_map<Cell, std::vector<int>, CellHash> cells;
  const auto cell_of = [&](int v) {
    return Cell{static_cast<std::int64_t>(std::floor(mesh.V(v, 0) / spacing)),
                static_cast<std::int64_t>(std::floor(mesh.V(v, 1) / spacing)),
                static_cast<std::int64_t>(std::floor(mesh.V(v, 2) / spacing))};
  };
  std::vector<int> centres;
  const double spacing2 = spacing * spacing;
  for (const int v : order) {
    const Cell c = cell_of(v);
    bool free = true;
    for (std::int64_t dx = -1; dx <= 1 && free; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && free; ++dy)
        for (std::int64_t dz = -1; dz <= 1 && free; ++dz) {
          const auto it = cells.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells.end()) continue;
          for (const int u : it->second)
            if ((mesh.V.row(u) - mesh.V.row(v)).squaredNorm() < spacing2) {
              free = false;
              break;
            }
        }
    if (!free) continue;
    cells[c].push_back(v);
    centres.push_back(v);
  }
  return centres;
}

// One bump: graph distances from `centre` up to `radius` (Dijkstra), as (vertex, value) pairs.
void bump(const Graph& g, int centre, double radius, std::vector<double>& distance, std::vector<int>& touched,
          std::vector<std::pair<int, double>>& out) {
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
  distance[static_cast<std::size_t>(centre)] = 0;
  touched.push_back(centre);
  heap.emplace(0.0, centre);
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (d > distance[static_cast<std::size_t>(v)]) continue;
    const double x = d / radius;
    out.emplace_back(v, (1 - x * x) * (1 - x * x));
    for (int e = g.offsets[static_cast<std::size_t>(v)]; e < g.offsets[static_cast<std::size_t>(v) + 1]; ++e) {
      const int u = g.neighbors[static_cast<std::size_t>(e)];
      const double du = d + g.lengths[static_cast<std::size_t>(e)];
      if (du >= radius || du >= distance[static_cast<std::size_t>(u)]) continue;
      if (distance[static_cast<std::size_t>(u)] == std::numeric_limits<double>::infinity()) touched.push_back(u);
      distance[static_cast<std::size_t>(u)] = du;
      heap.emplace(du, u);
    }
  }
  for (const int v : touched) distance[static_cast<std::size_t>(v)] = std::numeric_limits<double>::infinity();
  touched.clear();
  std::sort(out.begin(), out.end());
}

}  // namespace

BumpBasis multiscale_bumps(const Mesh& mesh, const BumpBasisOptions& options, const JobControl* control) {
  const auto n = static_cast<std::size_t>(mesh.V.rows());
  BumpBasis basis;
  const Graph g = edge_graph(mesh);

  // Components, and which are big enough to carry signal.
  UnionFind sets(n);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 1; k < 3; ++k) sets.unite(mesh.F(f, 0), mesh.F(f, k));
  std::vector<char> used(n, 0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(mesh.F(f, k))] = 1;
  std::unordered_map<int, int> size_of;
  for (std::size_t v = 0; v < n; ++v)
    if (used[v]) ++size_of[sets.find(static_cast<int>(v))];
  std::unordered_map<int, int> component_index;
  basis.component.assign(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    if (!used[v]) continue;
    const int root = sets.find(static_cast<int>(v));
    if (size_of[root] < options.min_component_vertices) {
      ++basis.skipped_vertices;
      continue;
    }
    const auto [it, inserted] = component_index.emplace(root, static_cast<int>(component_index.size()));
    basis.component[v] = it->second;
  }
  basis.marked_components = component_index.size();
  basis.skipped_components = size_of.size() - component_index.size();

  // Each marked vertex's share of the area (a third of each face's): the finest band's spacing
  // comes from the median share, so that on a mesh with dense and sparse regions (a low-poly
  // asset: big flat panels, detailed small parts) a bump still covers about the asked number
  // of vertices where most vertices are.
  std::vector<double> share(n, 0.0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    if (basis.component[static_cast<std::size_t>(mesh.F(f, 0))] >= 0) {
      const Eigen::RowVector3d a = mesh.V.row(mesh.F(f, 1)) - mesh.V.row(mesh.F(f, 0)),
                               b = mesh.V.row(mesh.F(f, 2)) - mesh.V.row(mesh.F(f, 0));
      for (int k = 0; k < 3; ++k) share[static_cast<std::size_t>(mesh.F(f, k))] += a.cross(b).norm() / 6;
    }
  std::vector<double> shares;
  for (std::size_t v = 0; v < n; ++v)
    if (basis.component[v] >= 0 && share[v] > 0) shares.push_back(share[v]);
  if (shares.empty()) return basis;
  std::nth_element(shares.begin(), shares.begin() + static_cast<long>(shares.size() / 2), shares.end());
  const double median_share = shares[shares.size() / 2];

  // A fixed scrambled order of the marked vertices (a multiplicative hash of the index).
  std::vector<int> order;
  for (std::size_t v = 0; v < n; ++v)
    if (basis.component[v] >= 0) order.push_back(static_cast<int>(v));
  std::sort(order.begin(), order.end(), [](int a, int b) {
    const auto ha = static_cast<std::uint32_t>(a) * 2654435761u, hb = static_cast<std::uint32_t>(b) * 2654435761u;
    return ha != hb ? ha < hb : a < b;
  });
  const std::vector<double> rough = vertex_roughness(mesh, g);

  // Bands fine to coarse: the finest spacing s makes a bump's disk (radius r·s) hold the asked
  // vertices at the median density; each coarser band doubles it, while it keeps min_bumps.
  struct Band {
    std::vector<int> centres;
    std::vector<std::vector<std::pair<int, double>>> columns;
  };
  std::vector<Band> fine_to_coarse;
  const double finest_spacing = std::sqrt(options.finest_support_vertices * median_share / M_PI) / options.radius;
  for (int k = 0; k < options.max_bands; ++k) {
    poll(control);
    const double spacing = finest_spacing * std::pow(2.0, k);
    Band band;
    // Centres 0.835 s apart: a maximal Poisson-disk set of about area / s² points.
    band.centres = spread_centres(mesh, order, 0.835 * spacing);
    if (static_cast<int>(band.centres.size()) < options.min_bumps) break;
    const double radius = options.radius * spacing;
    band.columns.resize(band.centres.size());
    parallel_for(
        static_cast<std::int64_t>(band.centres.size()), threads_of(control),
        [&](std::int64_t begin, std::int64_t end) {
          std::vector<double> distance(n, std::numeric_limits<double>::infinity());
          std::vector<int> touched;
          for (std::int64_t c = begin; c < end; ++c)
            bump(g, band.centres[static_cast<std::size_t>(c)], radius, distance, touched,
                 band.columns[static_cast<std::size_t>(c)]);
        },
        16);
    fine_to_coarse.push_back(std::move(band));
  }

  // Columns coarse to fine: band 0 is the coarsest.
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t b = 0; b < fine_to_coarse.size(); ++b) {
    const Band& band = fine_to_coarse[fine_to_coarse.size() - 1 - b];
    double covered = 0;
    for (std::size_t c = 0; c < band.centres.size(); ++c) {
      const auto column = static_cast<int>(basis.center.size());
      double weight = 0, roughness = 0;
      for (const auto& [v, value] : band.columns[c]) {
        entries.emplace_back(v, column, value);
        weight += value;
        roughness += value * rough[static_cast<std::size_t>(v)];
      }
      covered += static_cast<double>(band.columns[c].size());
      basis.center.push_back(band.centres[c]);
      basis.band.push_back(static_cast<int>(b));
      basis.roughness.push_back(weight > 0 ? roughness / weight : 0.0);
    }
    basis.band_support.push_back(covered / static_cast<double>(band.centres.size()));
  }
  basis.values.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(basis.center.size()));
  basis.values.setFromTriplets(entries.begin(), entries.end());
  return basis;
}

}  // namespace meshmark
