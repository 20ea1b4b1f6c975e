#include "core/grid/sphere_grid.hpp"

#include <cmath>
#include <stdexcept>

#include "core/mesh/edge_incidence.hpp"

namespace meshmark {

std::string to_string(BaseSolid base) {
  switch (base) {
    case BaseSolid::tetrahedron:
      return "tetra";
    case BaseSolid::octahedron:
      return "octa";
    case BaseSolid::icosahedron:
      return "icosa";
  }
  return "tetra";
}

BaseSolid parse_base_solid(const std::string& name) {
  if (name == "tetra" || name == "tetrahedron") return BaseSolid::tetrahedron;
  if (name == "octa" || name == "octahedron") return BaseSolid::octahedron;
  if (name == "icosa" || name == "icosahedron") return BaseSolid::icosahedron;
  throw std::invalid_argument("unknown base solid '" + name + "' (expected tetra, octa or icosa)");
}

namespace {

Mesh base_solid(BaseSolid base) {
  Mesh m;
  switch (base) {
    case BaseSolid::tetrahedron:
      m.V.resize(4, 3);
      m.V << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
      m.F.resize(4, 3);
      m.F << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
      break;
    case BaseSolid::octahedron:
      m.V.resize(6, 3);
      m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
      m.F.resize(8, 3);
      m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
      break;
    case BaseSolid::icosahedron: {
      const double t = (1 + std::sqrt(5.0)) / 2;
      m.V.resize(12, 3);
      m.V << -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, t, 0, -1, t, 0, 1, -t, 0,
          -1, -t, 0, 1;
      m.F.resize(20, 3);
      m.F << 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4,
          3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1;
      break;
    }
  }
  m.V.rowwise().normalize();
  return m;
}

// The vertex of face f that is neither a nor b.
int third_vertex(const Faces& F, int f, int a, int b) {
  for (int k = 0; k < 3; ++k)
    if (F(f, k) != a && F(f, k) != b) return F(f, k);
  return -1;
}

// Splits level j into level j+1: new vertices (one per edge, in sorted edge order), their
// stencils, and the child faces.
void refine(SphereGrid& grid, std::vector<Eigen::Vector3d>& points) {
  const Faces& F = grid.faces.back();
  const int vj = static_cast<int>(points.size());
  const EdgeIncidence inc = edge_incidence(F);
  const auto ne = inc.edges.rows();

  // The two faces of each edge: the one traversing it low→high, and the other.
  std::vector<std::array<int, 2>> edge_faces(static_cast<std::size_t>(ne), {-1, -1});
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int e = inc.face_edges(f, k);
      const bool along = F(f, k) < F(f, (k + 1) % 3);
      edge_faces[e][along ? 0 : 1] = static_cast<int>(f);
    }
  auto face_across = [&](int a, int b, int not_face) {  // the face on edge a–b other than not_face
    const int lo = std::min(a, b), hi = std::max(a, b);
    int e = -1;
    for (int k = 0; k < 3 && e < 0; ++k)  // the edge is one of not_face's three
      if (std::min(F(not_face, k), F(not_face, (k + 1) % 3)) == lo &&
          std::max(F(not_face, k), F(not_face, (k + 1) % 3)) == hi)
        e = inc.face_edges(not_face, k);
    return edge_faces[e][0] == not_face ? edge_faces[e][1] : edge_faces[e][0];
  };

  points.reserve(points.size() + static_cast<std::size_t>(ne));
  for (Eigen::Index e = 0; e < ne; ++e) {
    const int v1 = inc.edges(e, 0), v2 = inc.edges(e, 1);
    points.push_back((points[v1] + points[v2]).normalized());
    const int face1 = edge_faces[e][0], face2 = edge_faces[e][1];  // face1 runs v1→v2
    Stencil s;
    s.v1 = v1;
    s.v2 = v2;
    s.f1 = third_vertex(F, face1, v1, v2);
    s.f2 = third_vertex(F, face2, v1, v2);
    s.e[0] = third_vertex(F, face_across(v1, s.f1, face1), v1, s.f1);
    s.e[1] = third_vertex(F, face_across(s.f1, v2, face1), s.f1, v2);
    s.e[2] = third_vertex(F, face_across(v1, s.f2, face2), v1, s.f2);
    s.e[3] = third_vertex(F, face_across(s.f2, v2, face2), s.f2, v2);
    grid.stencils.push_back(s);
  }

  Faces children(4 * F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    const int ab = vj + inc.face_edges(f, 0), bc = vj + inc.face_edges(f, 1), ca = vj + inc.face_edges(f, 2);
    children.row(4 * f + 0) << a, ab, ca;
    children.row(4 * f + 1) << ab, b, bc;
    children.row(4 * f + 2) << ca, bc, c;
    children.row(4 * f + 3) << ab, bc, ca;
  }
  grid.faces.push_back(std::move(children));
  grid.vertex_counts.push_back(static_cast<int>(points.size()));
}

}  // namespace

long long sphere_grid_vertex_count(BaseSolid base, int level) {
  const long long v0 = base == BaseSolid::tetrahedron ? 4 : base == BaseSolid::octahedron ? 6 : 12;
  return 2 + (v0 - 2) * (1ll << (2 * level));
}

SphereGrid make_sphere_grid(BaseSolid base, int levels) {
  if (levels < 0 || levels > 12)
    throw std::invalid_argument("grid level " + std::to_string(levels) + " is outside 0..12");
  SphereGrid grid;
  grid.base = base;
  grid.levels = levels;
  const Mesh solid = base_solid(base);
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index v = 0; v < solid.V.rows(); ++v) points.push_back(solid.V.row(v));
  grid.vertex_counts.push_back(static_cast<int>(points.size()));
  grid.faces.push_back(solid.F);
  grid.stencils.reserve(static_cast<std::size_t>(sphere_grid_vertex_count(base, levels) - solid.V.rows()));
  for (int j = 0; j < levels; ++j) refine(grid, points);
  grid.points.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) grid.points.row(static_cast<Eigen::Index>(i)) = points[i];
  return grid;
}

int SphereGrid::level_of(int vertex) const {
  int level = 0;
  while (vertex >= vertex_counts[static_cast<std::size_t>(level)]) ++level;
  return level;
}

Eigen::Vector3d gnomonic_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c) {
  Eigen::Vector3d w(p.dot(b.cross(c)), a.dot(p.cross(c)), a.dot(b.cross(p)));
  w = w.cwiseMax(0.0);
  const double sum = w.sum();
  return sum > 0 ? Eigen::Vector3d(w / sum) : Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3);
}

namespace {

// How far inside the spherical triangle p is: the smallest of its three edge determinants.
double inside_margin(const Faces& F, const Vertices& P, int f, const Eigen::Vector3d& p) {
  const Eigen::Vector3d a = P.row(F(f, 0)), b = P.row(F(f, 1)), c = P.row(F(f, 2));
  return std::min({a.cross(b).dot(p), b.cross(c).dot(p), c.cross(a).dot(p)});
}

}  // namespace

int descend_grid(const SphereGrid& grid, const Eigen::Vector3d& p, int from_level, int face, int level) {
  int best = face;
  if (from_level < 0) {
    double best_margin = -std::numeric_limits<double>::infinity();
    for (int f = 0; f < grid.faces[0].rows(); ++f) {
      const double m = inside_margin(grid.faces[0], grid.points, f, p);
      if (m > best_margin) best_margin = m, best = f;
    }
    from_level = 0;
  }
  for (int j = from_level + 1; j <= level; ++j) {
    const int parent = best;
    double best_margin = -std::numeric_limits<double>::infinity();
    for (int child = 4 * parent; child < 4 * parent + 4; ++child) {
      const double m = inside_margin(grid.faces[j], grid.points, child, p);
      if (m > best_margin) best_margin = m, best = child;
    }
  }
  return best;
}

GridLocation grid_location(const SphereGrid& grid, const Eigen::Vector3d& p, int level, int face) {
  const Faces& F = grid.faces[static_cast<std::size_t>(level)];
  return {face, gnomonic_barycentric(p, grid.points.row(F(face, 0)), grid.points.row(F(face, 1)),
                                     grid.points.row(F(face, 2)))};
}

GridLocation locate_in_grid(const SphereGrid& grid, const Eigen::Vector3d& p, int level) {
  return grid_location(grid, p, level, descend_grid(grid, p, -1, 0, level));
}

}  // namespace meshmark
