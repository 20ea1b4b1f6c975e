#include "core/attacks/simplify.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "core/mesh/collapse_is_safe.hpp"
#include "core/mesh/move_folds_faces.hpp"
#include "core/mesh/openmesh_convert.hpp"

namespace meshmark {

namespace {

using Quadric = Eigen::Matrix4d;  // Σ area · p pᵀ over planes p = (n, −n·x)

struct Candidate {
  double cost;
  int edge;
  int version;
  bool operator>(const Candidate& o) const { return std::tie(cost, edge) > std::tie(o.cost, o.edge); }
};

class QuadricSimplifier {
 public:
  explicit QuadricSimplifier(const Mesh& input) : mesh_(to_halfedge_mesh(input, NonManifoldFaces::detach)) {
    mesh_.request_vertex_status();
    mesh_.request_edge_status();
    mesh_.request_face_status();
    quadric_.assign(mesh_.n_vertices(), Quadric::Zero());
    for (const auto f : mesh_.faces()) {
      auto it = mesh_.cfv_iter(f);
      const Eigen::Vector3d a = point(*it), b = point(*++it), c = point(*++it);
      const Eigen::Vector3d n2 = (b - a).cross(c - a);
      const double area = 0.5 * n2.norm();
      if (area <= 0) continue;
      const Eigen::Vector3d n = n2.normalized();
      const Eigen::Vector4d p(n.x(), n.y(), n.z(), -n.dot(a));
      for (const auto v : mesh_.fv_range(f)) quadric_[v.idx()] += area * p * p.transpose();
    }
    add_boundary_quadrics();
    version_.assign(mesh_.n_edges(), 0);
    target_.resize(mesh_.n_edges());
    for (const auto e : mesh_.edges()) push(e);
  }

  Mesh run(std::size_t keep) {
    std::size_t alive = mesh_.n_vertices();
    while (alive > keep && !queue_.empty()) {
      const Candidate c = queue_.top();
      queue_.pop();
      const auto e = mesh_.edge_handle(c.edge);
      if (c.version != version_[c.edge] || mesh_.status(e).deleted() || !std::isfinite(c.cost)) continue;
      if (!collapse(e)) continue;
      --alive;
    }
    return from_halfedge_mesh(mesh_);
  }

 private:
  Eigen::Vector3d point(HalfedgeMesh::VertexHandle v) const {
    const auto& p = mesh_.point(v);
    return {p[0], p[1], p[2]};
  }

  // Garland and Heckbert's boundary constraint: each boundary edge adds a heavily weighted plane
  // through it, perpendicular to its face, so that holes and open edges keep their outline
  // instead of being eaten (as any quadric simplifier that preserves boundaries does).
  void add_boundary_quadrics() {
    constexpr double kBoundaryWeight = 100;
    for (const auto h : mesh_.halfedges()) {
      if (!mesh_.is_boundary(h)) continue;
      const auto inner = mesh_.opposite_halfedge_handle(h);
      const auto a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
      const auto c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(inner));
      const Eigen::Vector3d pa = point(a), pb = point(b), pc = point(c);
      const Eigen::Vector3d face_normal = (pa - pb).cross(pc - pb);
      const Eigen::Vector3d m = (pb - pa).cross(face_normal);
      if (!(m.norm() > 0)) continue;
      const Eigen::Vector3d n = m.normalized();
      const Eigen::Vector4d plane(n.x(), n.y(), n.z(), -n.dot(pa));
      const Quadric q = kBoundaryWeight * (pb - pa).squaredNorm() * plane * plane.transpose();
      quadric_[a.idx()] += q;
      quadric_[b.idx()] += q;
    }
  }

  // The position minimizing the summed quadric (or the best of the ends and midpoint).
  std::pair<Eigen::Vector3d, double> optimum(const Quadric& Q, const Eigen::Vector3d& a,
                                             const Eigen::Vector3d& b) const {
    auto error = [&](const Eigen::Vector3d& x) {
      return Eigen::Vector4d(x.x(), x.y(), x.z(), 1).dot(Q * Eigen::Vector4d(x.x(), x.y(), x.z(), 1));
    };
    const Eigen::Matrix3d A = Q.topLeftCorner<3, 3>();
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(A);
    std::pair<Eigen::Vector3d, double> best{a, error(a)};
    for (const Eigen::Vector3d& x : {b, Eigen::Vector3d(0.5 * (a + b))})
      if (const double e = error(x); e < best.second) best = {x, e};
    if (lu.rank() == 3) {
      const Eigen::Vector3d x = lu.solve(-Q.topRightCorner<3, 1>());
      // Accept the optimum only near the edge: far placements on flat regions are unstable.
      if ((x - 0.5 * (a + b)).norm() < 2 * (a - b).norm())
        if (const double e = error(x); e <= best.second) best = {x, e};
    }
    best.second = std::max(best.second, 0.0);
    return best;
  }

  void push(HalfedgeMesh::EdgeHandle e) {
    const auto h = mesh_.halfedge_handle(e, 0);
    const auto v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
    const auto [x, cost] = optimum(quadric_[v0.idx()] + quadric_[v1.idx()], point(v0), point(v1));
    target_[e.idx()] = x;
    queue_.push({cost, e.idx(), ++version_[e.idx()]});
  }

  // Would moving the faces around v (except those on the collapsing edge) to x fold one over?
  bool folds(HalfedgeMesh::VertexHandle v, HalfedgeMesh::VertexHandle other, const Eigen::Vector3d& x) const {
    return move_folds_faces(mesh_, v, other, x, 0.2);
  }

  bool collapse(HalfedgeMesh::EdgeHandle e) {
    auto h = mesh_.halfedge_handle(e, 0);
    if (!collapse_is_safe(mesh_, h)) {
      h = mesh_.halfedge_handle(e, 1);
      if (!collapse_is_safe(mesh_, h)) return false;
    }
    const auto gone = mesh_.from_vertex_handle(h), kept = mesh_.to_vertex_handle(h);
    const Eigen::Vector3d x = target_[e.idx()];
    if (folds(gone, kept, x) || folds(kept, gone, x)) return false;
    quadric_[kept.idx()] += quadric_[gone.idx()];
    mesh_.collapse(h);
    mesh_.set_point(kept, HalfedgeMesh::Point(x.x(), x.y(), x.z()));
    for (const auto e2 : mesh_.ve_range(kept)) push(e2);
    return true;
  }

  HalfedgeMesh mesh_;
  std::vector<Quadric> quadric_;
  std::vector<int> version_;
  std::vector<Eigen::Vector3d> target_;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue_;
};

}  // namespace

Mesh simplify(const Mesh& mesh, double fraction) {
  if (!(fraction > 0 && fraction <= 1)) throw std::invalid_argument("the kept fraction must be in (0, 1]");
  const auto keep =
      std::max<std::size_t>(4, static_cast<std::size_t>(std::lround(fraction * static_cast<double>(mesh.V.rows()))));
  QuadricSimplifier simplifier(mesh);
  return simplifier.run(keep);
}

}  // namespace meshmark
