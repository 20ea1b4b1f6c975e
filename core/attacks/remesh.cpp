#include "core/attacks/remesh.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/mesh/edge_incidence.hpp"
#include "core/mesh/collapse_is_safe.hpp"
#include "core/mesh/move_folds_faces.hpp"
#include "core/mesh/openmesh_convert.hpp"
#include "core/spatial/aabb_tree.hpp"

namespace meshmark {

namespace {

using VH = HalfedgeMesh::VertexHandle;
using Point = HalfedgeMesh::Point;

Eigen::Vector3d to_eigen(const Point& p) { return {p[0], p[1], p[2]}; }
Point to_point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

double mean_edge_length(const Mesh& mesh) {
  const EdgeIncidence inc = edge_incidence(mesh.F);
  double sum = 0;
  for (Eigen::Index e = 0; e < inc.edges.rows(); ++e)
    sum += (mesh.V.row(inc.edges(e, 0)) - mesh.V.row(inc.edges(e, 1))).norm();
  return sum / static_cast<double>(inc.edges.rows());
}

class Remesher {
 public:
  Remesher(const Mesh& input, double length, const AabbTree& surface, double max_surface_distance)
      : mesh_(to_halfedge_mesh(input, NonManifoldFaces::detach)),
        high_(4.0 / 3.0 * length),
        low_(0.8 * length),
        surface_(surface),
        max_distance_(max_surface_distance) {
    mesh_.request_vertex_status();
    mesh_.request_edge_status();
    mesh_.request_face_status();
  }

  void split_long_edges() {
    // Only the edges there at the start: a nearly flat triangle can make each split create an
    // edge as long as the one split, so a pass that chased new edges might never end. Edges
    // still long are split by the next pass.
    const std::size_t existing = mesh_.n_edges();
    for (std::size_t e = 0; e < existing; ++e) {
      const auto eh = mesh_.edge_handle(static_cast<int>(e));
      if (mesh_.status(eh).deleted() || length(eh) <= high_) continue;
      const auto h = mesh_.halfedge_handle(eh, 0);
      const Point a = mesh_.point(mesh_.from_vertex_handle(h)), b = mesh_.point(mesh_.to_vertex_handle(h));
      const Point mid = (a + b) * 0.5;
      if (mid == a || mid == b) continue;  // below the coordinates' precision: a split would not shorten it
      mesh_.split(eh, mid);
    }
  }

  void collapse_short_edges() {
    for (std::size_t e = 0; e < mesh_.n_edges(); ++e) {
      const auto eh = mesh_.edge_handle(static_cast<int>(e));
      if (mesh_.status(eh).deleted() || length(eh) >= low_) continue;
      for (int side = 0; side < 2; ++side) {
        const auto h = mesh_.halfedge_handle(eh, side);
        const VH gone = mesh_.from_vertex_handle(h), kept = mesh_.to_vertex_handle(h);
        // A boundary stays where it is: it never merges into the interior, and an interior vertex
        // merging into it takes the boundary vertex's place.
        const bool gone_on_boundary = mesh_.is_boundary(gone), kept_on_boundary = mesh_.is_boundary(kept);
        if (gone_on_boundary && !(kept_on_boundary && mesh_.is_boundary(eh))) continue;
        const Point at =
            kept_on_boundary && !gone_on_boundary ? mesh_.point(kept) : (mesh_.point(gone) + mesh_.point(kept)) * 0.5;
        if (!collapse_is_safe(mesh_, h) || makes_long_edge(gone, kept, at) || folds(gone, kept, at) ||
            folds(kept, gone, at) || collapse_leaves_surface(gone, kept, at))
          continue;
        mesh_.collapse(h);
        mesh_.set_point(kept, at);
        break;
      }
    }
  }

  void equalize_valences() {
    for (const auto eh : mesh_.edges()) {
      if (mesh_.status(eh).deleted() || mesh_.is_boundary(eh) || !mesh_.is_flip_ok(eh)) continue;
      const auto h0 = mesh_.halfedge_handle(eh, 0), h1 = mesh_.halfedge_handle(eh, 1);
      const VH a = mesh_.to_vertex_handle(h0), b = mesh_.to_vertex_handle(h1);
      const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h0)),
               d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h1));
      auto deviation = [&](int va, int vb, int vc, int vd) {
        return std::abs(va - 6) + std::abs(vb - 6) + std::abs(vc - 6) + std::abs(vd - 6);
      };
      const int va = static_cast<int>(mesh_.valence(a)), vb = static_cast<int>(mesh_.valence(b)),
                vc = static_cast<int>(mesh_.valence(c)), vd = static_cast<int>(mesh_.valence(d));
      if (deviation(va - 1, vb - 1, vc + 1, vd + 1) < deviation(va, vb, vc, vd) && !flip_folds(a, b, c, d) &&
          !off_surface((to_eigen(mesh_.point(c)) + to_eigen(mesh_.point(d))) / 2))
        mesh_.flip(eh);
    }
  }

  void relax_and_project() {
    const AabbTree& surface = surface_;
    mesh_.request_face_normals();
    mesh_.request_vertex_normals();
    mesh_.update_normals();
    std::vector<Point> target(mesh_.n_vertices());
    for (const auto v : mesh_.vertices()) target[v.idx()] = mesh_.point(v);
    for (const auto v : mesh_.vertices()) {
      if (mesh_.status(v).deleted() || mesh_.is_boundary(v)) continue;  // a boundary keeps its outline
      if (is_sharp(v)) continue;  // a tip or a corner: relaxing it would round it off
      Point centroid(0, 0, 0);
      int n = 0;
      for (const auto u : mesh_.vv_range(v)) centroid += mesh_.point(u), ++n;
      if (n == 0) continue;
      centroid /= n;
      const Eigen::Vector3d p = to_eigen(mesh_.point(v)), q = to_eigen(centroid), normal = to_eigen(mesh_.normal(v));
      const Eigen::Vector3d moved = q + normal * normal.dot(p - q);  // move only in the tangent plane
      if (moved.allFinite()) target[v.idx()] = to_point(moved);      // a degenerate fan has no normal: stay
    }
    for (const auto v : mesh_.vertices())
      if (!mesh_.status(v).deleted())
        mesh_.set_point(v, to_point(surface.closest_point(to_eigen(target[v.idx()]))->point));
    mesh_.release_vertex_normals();
    mesh_.release_face_normals();
  }

  Mesh result() { return from_halfedge_mesh(mesh_); }

 private:
  double length(HalfedgeMesh::EdgeHandle e) const { return mesh_.calc_edge_length(e); }

  bool makes_long_edge(VH gone, VH kept, const Point& at) const {
    for (const VH u : {gone, kept})
      for (const auto w : mesh_.vv_range(u))
        if (w != gone && w != kept && (mesh_.point(w) - at).norm() > high_) return true;
    return false;
  }

  // Some face around v turns more than 45 degrees away from v's normal.
  bool is_sharp(VH v) const {
    const Eigen::Vector3d normal = to_eigen(mesh_.normal(v));
    for (const auto f : mesh_.vf_range(v))
      if (to_eigen(mesh_.normal(f)).dot(normal) < std::cos(M_PI / 4)) return true;
    return false;
  }

  bool off_surface(const Eigen::Vector3d& p) const {
    return surface_.closest_point(p)->distance_squared > max_distance_ * max_distance_;
  }

  // Would the faces around the merged vertex leave the input surface (cutting off a thin tip or
  // a crease, as a remesher with a surface-distance check refuses to)? Their centroids and the
  // midpoints of their edges to the merged vertex are the samples.
  bool collapse_leaves_surface(VH gone, VH kept, const Point& at) const {
    const Eigen::Vector3d p = to_eigen(at);
    if (off_surface(p)) return true;
    for (const VH u : {gone, kept})
      for (const auto f : mesh_.vf_range(u)) {
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        bool removed = false;
        for (const VH w : mesh_.fv_range(f)) {
          if ((w == gone || w == kept) && w != u) removed = true;  // a face on the collapsed edge
          centroid += (w == gone || w == kept) ? p : to_eigen(mesh_.point(w));
        }
        if (removed) continue;
        if (off_surface(centroid / 3)) return true;
      }
    for (const VH u : {gone, kept})
      for (const auto w : mesh_.vv_range(u))
        if (w != gone && w != kept && off_surface((p + to_eigen(mesh_.point(w))) / 2)) return true;
    return false;
  }

  // Would moving v to `at` (with `other` merged into it) turn a face around v over?
  bool folds(VH v, VH other, const Point& at) const { return move_folds_faces(mesh_, v, other, to_eigen(at), 0.1); }

  // Flipping edge a–b (faces a b c and b a d) to c–d: would the new faces turn away?
  bool flip_folds(VH a, VH b, VH c, VH d) const {
    const Eigen::Vector3d pa = to_eigen(mesh_.point(a)), pb = to_eigen(mesh_.point(b)), pc = to_eigen(mesh_.point(c)),
                          pd = to_eigen(mesh_.point(d));
    const Eigen::Vector3d n_old = (pb - pa).cross(pc - pa) + (pa - pb).cross(pd - pb);
    const Eigen::Vector3d n1 = (pd - pc).cross(pa - pc), n2 = (pc - pd).cross(pb - pd);
    return n1.dot(n_old) <= 0 || n2.dot(n_old) <= 0;
  }

  HalfedgeMesh mesh_;
  double high_, low_;
  const AabbTree& surface_;
  double max_distance_;
};

}  // namespace

Mesh remesh(const Mesh& mesh, const RemeshOptions& options) {
  const double length = options.target_edge_length > 0 ? options.target_edge_length : mean_edge_length(mesh);
  const double scale = mesh.V.size() > 0 ? mesh.V.cwiseAbs().maxCoeff() : 0.0;
  if (!(length > 1e-12 * scale) || !std::isfinite(length))
    throw std::invalid_argument("cannot remesh: the mesh's edges are below the precision of its coordinates");
  const AabbTree surface(mesh.V, mesh.F);
  const double diagonal = mesh.V.rows() > 0 ? (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm() : 0.0;
  Remesher remesher(mesh, length, surface, options.max_surface_distance * diagonal);
  for (int it = 0; it < options.iterations; ++it) {
    remesher.split_long_edges();
    remesher.collapse_short_edges();
    remesher.equalize_valences();
    remesher.relax_and_project();
  }
  return remesher.result();
}

}  // namespace meshmark
