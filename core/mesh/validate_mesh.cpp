#include "core/mesh/validate_mesh.hpp"

#include <algorithm>
#include <map>
#include <cstdio>
#include <future>
#include <numeric>
#include <optional>
#include <tuple>
#include <utility>

#include "core/mesh/coordinate_precision.hpp"
#include "core/mesh/edge_incidence.hpp"
#include "core/mesh/surface_moments.hpp"
#include "core/mesh/vertex_faces.hpp"
#include "core/util/union_find.hpp"

namespace meshmark {

std::string to_string(Orientation orientation) {
  switch (orientation) {
    case Orientation::outward:
      return "outward";
    case Orientation::inward:
      return "inward";
    case Orientation::inconsistent:
      return "inconsistent";
  }
  return "inconsistent";
}

namespace {

std::string vertex_words(const Mesh& mesh, int v) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "vertex %d at (%.7g, %.7g, %.7g)", v, mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2));
  return buffer;
}

std::string plural(std::size_t n, const std::string& word) {
  if (n == 1) return "1 " + word;
  if (word.size() >= 6 && word.compare(word.size() - 6, 6, "vertex") == 0)
    return std::to_string(n) + " " + word.substr(0, word.size() - 2) + "ices";
  return std::to_string(n) + " " + word + "s";
}

// Number of edge-connected fans the faces around `v` form. `others` is scratch space, kept by the
// caller: allocating it for every vertex was a tenth of validating a large mesh.
int count_fans(const Faces& F, const VertexFaces& vf, int v, std::vector<std::pair<int, int>>& others) {
  const int begin = vf.offsets[v], end = vf.offsets[v + 1];
  others.clear();  // (other vertex of an edge through v, local face)
  for (int i = begin; i < end; ++i) {
    const int f = vf.faces[i];
    for (int k = 0; k < 3; ++k)
      if (F(f, k) != v) others.emplace_back(F(f, k), i - begin);
  }
  std::sort(others.begin(), others.end());
  UnionFind fans(static_cast<std::size_t>(end - begin));
  for (std::size_t i = 1; i < others.size(); ++i)
    if (others[i].first == others[i - 1].first) fans.unite(others[i].second, others[i - 1].second);
  int count = 0;
  for (int i = 0; i < end - begin; ++i) count += fans.find(i) == i ? 1 : 0;
  return count;
}

void check_edges(const Mesh& mesh, const EdgeIncidence& inc, const ValidateOptions& options, MeshReport& r) {
  UnionFind loops(static_cast<std::size_t>(mesh.V.rows()));
  std::vector<char> on_boundary(static_cast<std::size_t>(mesh.V.rows()), 0);
  for (std::size_t e = 0; e < inc.face_count.size(); ++e) {
    const std::array<int, 2> ends{inc.edges(e, 0), inc.edges(e, 1)};
    if (inc.face_count[e] == 1) {
      if (r.boundary_edges++ < options.max_examples) r.boundary_edge_examples.push_back(ends);
      loops.unite(ends[0], ends[1]);
      on_boundary[ends[0]] = on_boundary[ends[1]] = 1;
    } else if (inc.face_count[e] > 2) {
      if (r.nonmanifold_edges++ < options.max_examples) r.nonmanifold_edge_examples.push_back(ends);
    }
  }
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (on_boundary[v] && loops.find(static_cast<int>(v)) == v) ++r.boundary_loops;
}

Orientation check_orientation(const Mesh& mesh, const EdgeIncidence& inc, UnionFind& pieces) {
  for (std::size_t e = 0; e < inc.face_count.size(); ++e)
    if (inc.face_count[e] == 2 && inc.along_count[e] != 1) return Orientation::inconsistent;
  // Signed volume per component, about the vertex centroid.
  const Eigen::RowVector3d center = mesh.V.colwise().mean();
  std::vector<double> volume(static_cast<std::size_t>(mesh.V.rows()), 0.0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)) - center, b = mesh.V.row(mesh.F(f, 1)) - center,
                          c = mesh.V.row(mesh.F(f, 2)) - center;
    volume[pieces.find(mesh.F(f, 0))] += a.dot(b.cross(c));
  }
  bool any_out = false, any_in = false;
  for (double v : volume) {
    any_out = any_out || v > 0;
    any_in = any_in || v < 0;
  }
  if (any_out && any_in) return Orientation::inconsistent;
  return any_in ? Orientation::inward : Orientation::outward;
}

// What validation finds from the positions alone, apart from the connectivity's checks.
struct PositionFindings {
  std::size_t zero_area_faces = 0;
  std::vector<int> zero_area_face_examples;
  std::size_t duplicate_vertices = 0;
  std::optional<std::string> precision_problem;
  Eigen::Vector3d variances = Eigen::Vector3d::Zero();  ///< principal variances of the surface
};

std::size_t count_duplicates(const Mesh& mesh) {
  std::vector<int> order(static_cast<std::size_t>(mesh.V.rows()));
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    for (int k = 0; k < 3; ++k)
      if (mesh.V(a, k) != mesh.V(b, k)) return mesh.V(a, k) < mesh.V(b, k);
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::size_t duplicates = 0;
  for (std::size_t i = 1; i < order.size(); ++i)
    if (mesh.V.row(order[i]) == mesh.V.row(order[i - 1])) ++duplicates;
  return duplicates;
}

PositionFindings check_positions(const Mesh& mesh, double diagonal, const ValidateOptions& options) {
  PositionFindings found;
  const double min_double_area = 2 * options.zero_area_tolerance * diagonal * diagonal;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    if ((b - a).cross(c - a).norm() <= min_double_area)
      if (found.zero_area_faces++ < options.max_examples) found.zero_area_face_examples.push_back(static_cast<int>(f));
  }
  found.duplicate_vertices = count_duplicates(mesh);
  found.precision_problem = coordinate_precision_problem(mesh.V);
  found.variances = surface_moments(mesh).variances;
  return found;
}

void describe_problems(const Mesh& mesh, const Eigen::Vector3d& variances, MeshReport& r) {
  auto& p = r.sphere_problems;
  if (r.faces == 0) p.push_back("the mesh has no faces");
  const std::size_t used = r.vertices - r.isolated_vertices;
  if (r.faces > 0 && used < 4)
    p.push_back("the faces use only " + plural(used, "vertex") + "; a closed surface needs at least 4 (a tetrahedron)");
  if (r.components > 1) p.push_back(plural(r.components, "connected component") + ": the sphere takes one surface");
  if (r.boundary_edges > 0) {
    const auto& e = r.boundary_edge_examples.front();
    p.push_back(plural(r.boundary_loops, "boundary loop") + " (" + plural(r.boundary_edges, "boundary edge") +
                ", e.g. the edge from vertex " + std::to_string(e[0]) + " to " + std::to_string(e[1]) +
                "): the surface has holes");
  }
  if (r.nonmanifold_edges > 0) {
    const auto& e = r.nonmanifold_edge_examples.front();
    p.push_back(plural(r.nonmanifold_edges, "non-manifold edge") +
                " (used by more than two faces, e.g. the edge from vertex " + std::to_string(e[0]) + " to " +
                std::to_string(e[1]) + ")");
  }
  if (r.nonmanifold_vertices > 0) {
    std::string names;
    for (int v : r.nonmanifold_vertex_examples) names += (names.empty() ? "" : "; ") + vertex_words(mesh, v);
    p.push_back(plural(r.nonmanifold_vertices, "non-manifold (pinch) vertex") +
                " where separate fans of faces touch: " + names);
  }
  if (r.genus && *r.genus > 0)
    p.push_back("genus " + std::to_string(*r.genus) + " (the surface has " +
                plural(static_cast<std::size_t>(*r.genus), "handle") +
                "): only genus-0, sphere-like surfaces can be mapped to the sphere");
  if (!r.genus && r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0 && r.faces > 0)
    p.push_back("the Euler characteristic " + std::to_string(r.euler_characteristic) + " gives no whole genus");
  if (r.orientation == Orientation::inconsistent && r.nonmanifold_edges == 0)
    p.push_back("the faces are not consistently oriented (neighbouring faces wind in opposite directions)");
  if (r.zero_area_faces > 0)
    p.push_back(plural(r.zero_area_faces, "zero-area face") + " (e.g. face " +
                std::to_string(r.zero_area_face_examples.front()) + ")");
  if (r.isolated_vertices > 0) p.push_back(plural(r.isolated_vertices, "isolated vertex") + " that no face uses");
  if (r.duplicate_vertices > 0)
    r.warnings.push_back(plural(r.duplicate_vertices, "vertex") + " at exactly the position of another vertex");
  if (r.orientation == Orientation::inward)
    r.warnings.push_back("all faces wind inward; the pipeline reads them outward");
  if (const Eigen::Vector3d& v = variances; v[2] > 0 && variances_alike(v[0], v[1]) && variances_alike(v[1], v[2]))
    r.warnings.push_back(
        "the shape is about as wide every way (its principal variances within 10 % of each other, as a ball's): "
        "a turned copy registers only by the vertices it kept (not once remeshed), and embed refuses a copy that "
        "does not read back turned");
}

// The components below the floor that carries a mark, and the vertices they hold: parts of
// kMinMarkedComponentVertices, or of kMinLowPolyComponentVertices when the larger parts alone
// hold fewer than kMinMarkedVertices.
void count_small_components(const Mesh& mesh, const VertexFaces& vf, UnionFind& pieces, MeshReport& r) {
  std::map<int, std::size_t> size;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (vf.offsets[v] != vf.offsets[v + 1]) ++size[pieces.find(static_cast<int>(v))];
  const auto count_below = [&](std::size_t floor) {
    r.marked_component_floor = floor;
    r.small_components = r.small_component_vertices = 0;
    std::size_t marked = 0;
    for (const auto& [root, n] : size)
      if (n < floor) ++r.small_components, r.small_component_vertices += n;
      else marked += n;
    return marked;
  };
  if (count_below(kMinMarkedComponentVertices) < kMinMarkedVertices) count_below(kMinLowPolyComponentVertices);
}

// The basis: the sphere wherever the paper's method applies (as it is, or once a genus-0
// surface's holes are closed virtually), bumps on the mesh for everything else that has enough
// real surface; nothing, with the reason, for the rest.
void choose_basis(MeshReport& r) {
  const std::size_t used = r.vertices - r.isolated_vertices;
  const std::size_t marked = used - r.small_component_vertices;  // small parts carry nothing
  if (r.faces == 0) r.problems.push_back("the mesh has no faces (a point cloud cannot be watermarked)");
  else if (r.zero_area_faces == r.faces) r.problems.push_back("every face has zero area: there is no surface to mark");
  else if (used < kMinMarkedVertices)
    r.problems.push_back("the faces use only " + plural(used, "vertex") +
                         ": too few to carry a mark that a detection can tell from chance (even 4 bits read right "
                         "stay inconclusive); 16 bits need at least " +
                         std::to_string(kMinMarkedVertices));
  else if (marked < kMinMarkedVertices)
    r.problems.push_back("only " + plural(marked, "vertex") + " lie in parts of at least " +
                         std::to_string(r.marked_component_floor) +
                         " vertices (smaller parts carry no watermark); watermarking needs at least " +
                         std::to_string(kMinMarkedVertices));
  if (!r.problems.empty()) return;
  if (r.closed_genus_zero) {
    r.basis = MeshBasis::sphere;
    r.basis_reason = "one closed genus-0 surface: spherical wavelets on its spherical map (the paper's method)";
    return;
  }
  const bool fillable = r.components == 1 && r.boundary_loops > 0 && r.nonmanifold_edges == 0 &&
                        r.nonmanifold_vertices == 0 && r.orientation != Orientation::inconsistent &&
                        r.zero_area_faces == 0 && r.genus && *r.genus == 0;
  if (fillable) {
    r.basis = MeshBasis::sphere_filled;
    r.basis_reason =
        "one genus-0 surface with " + plural(r.boundary_loops, "hole") +
        ": the holes are closed virtually for the spherical map only (the filling never reaches the output)";
    return;
  }
  r.basis = MeshBasis::bumps;
  std::string why;
  if (r.components > 1) why += plural(r.components, "component") + ", ";
  if (r.genus && *r.genus > 0) why += "genus " + std::to_string(*r.genus) + ", ";
  if (r.boundary_loops > 0) why += plural(r.boundary_loops, "hole") + ", ";
  if (r.nonmanifold_edges > 0) why += plural(r.nonmanifold_edges, "non-manifold edge") + ", ";
  if (r.nonmanifold_vertices > 0) why += plural(r.nonmanifold_vertices, "pinch vertex") + ", ";
  if (r.orientation == Orientation::inconsistent) why += "inconsistent winding, ";
  if (r.zero_area_faces > 0) why += plural(r.zero_area_faces, "zero-area face") + ", ";
  if (r.isolated_vertices > 0) why += plural(r.isolated_vertices, "isolated vertex") + ", ";
  if (why.empty())
    why = r.sphere_problems.empty() ? std::string("no spherical map, ") : r.sphere_problems.front() + ", ";
  why.resize(why.size() - 2);
  r.basis_reason = "no spherical map (" + why + "): multiscale bumps on the mesh itself";
  if (r.small_components > 0)
    r.warnings.push_back(plural(r.small_components, "component") + " below " +
                         std::to_string(r.marked_component_floor) +
                         " vertices will carry no watermark (left as they are)");
}

}  // namespace

std::string to_string(MeshBasis basis) {
  switch (basis) {
    case MeshBasis::none:
      return "none";
    case MeshBasis::sphere:
      return "sphere";
    case MeshBasis::sphere_filled:
      return "sphere-filled";
    case MeshBasis::bumps:
      return "bumps";
  }
  return "none";
}

MeshReport validate_mesh(const Mesh& mesh, const ValidateOptions& options) {
  MeshReport r;
  r.vertices = static_cast<std::size_t>(mesh.V.rows());
  r.faces = static_cast<std::size_t>(mesh.F.rows());
  if (mesh.V.rows() > 0) r.bbox_diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  // The positions' checks beside the connectivity's when a second thread is there: at millions
  // of vertices each takes seconds.
  std::future<PositionFindings> positions =
      std::async(options.threads > 1 ? std::launch::async : std::launch::deferred,
                 [&mesh, &options, diagonal = r.bbox_diagonal] { return check_positions(mesh, diagonal, options); });

  const EdgeIncidence inc = edge_incidence(mesh.F);
  const VertexFaces vf = vertex_faces(mesh.F, mesh.V.rows());
  UnionFind pieces(r.vertices);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    pieces.unite(mesh.F(f, 0), mesh.F(f, 1));
    pieces.unite(mesh.F(f, 0), mesh.F(f, 2));
  }
  std::size_t used = 0;
  std::vector<std::pair<int, int>> fan_scratch;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const int vi = static_cast<int>(v);
    if (vf.offsets[v] == vf.offsets[v + 1]) {
      ++r.isolated_vertices;
      continue;
    }
    ++used;
    if (pieces.find(vi) == vi) ++r.components;
    if (count_fans(mesh.F, vf, vi, fan_scratch) > 1)
      if (r.nonmanifold_vertices++ < options.max_examples) r.nonmanifold_vertex_examples.push_back(vi);
  }
  check_edges(mesh, inc, options, r);
  r.orientation = check_orientation(mesh, inc, pieces);

  r.euler_characteristic =
      static_cast<long long>(used) - static_cast<long long>(inc.face_count.size()) + static_cast<long long>(r.faces);
  const long long twice_genus =
      2 * static_cast<long long>(r.components) - r.euler_characteristic - static_cast<long long>(r.boundary_loops);
  if (r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0 && twice_genus >= 0 && twice_genus % 2 == 0)
    r.genus = static_cast<int>(twice_genus / 2);

  PositionFindings found = positions.get();
  r.zero_area_faces = found.zero_area_faces;
  r.zero_area_face_examples = std::move(found.zero_area_face_examples);
  r.duplicate_vertices = found.duplicate_vertices;
  describe_problems(mesh, found.variances, r);
  if (const auto& lost = found.precision_problem) {
    r.sphere_problems.push_back(*lost);
    r.problems.push_back(*lost);
  }
  r.closed_genus_zero = r.sphere_problems.empty();
  count_small_components(mesh, vf, pieces, r);
  choose_basis(r);
  r.valid = r.basis != MeshBasis::none;
  return r;
}

}  // namespace meshmark
