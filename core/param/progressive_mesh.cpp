#include "core/param/progressive_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/mesh/openmesh_convert.hpp"

namespace meshmark {

namespace {

struct Candidate {
  int edge;
  int version;
};

// A priority queue of edges by cost, approximately: costs fall into buckets a quarter octave
// wide, each a stack. Pushing and popping are O(1) and touch memory near the last touched, where
// an exact binary heap of millions of lazily invalidated entries spent 80 % of the time on cache
// misses (557k vertices: 14 s). Collapsing within a quarter octave in stack order instead of
// by exact cost changes nothing that matters here.
class BucketQueue {
 public:
  void push(double cost, Candidate c) {
    const std::size_t b = bucket_of(cost);
    if (b >= buckets_.size()) buckets_.resize(b + 1);
    buckets_[b].push_back(c);
    lowest_ = std::min(lowest_, b);
    ++size_;
  }
  bool empty() const { return size_ == 0; }
  Candidate pop() {
    while (buckets_[lowest_].empty()) ++lowest_;
    const Candidate c = buckets_[lowest_].back();
    buckets_[lowest_].pop_back();
    --size_;
    return c;
  }

 private:
  static std::size_t bucket_of(double cost) {
    if (!(cost > 0)) return 0;
    int exponent = 0;
    const double mantissa = std::frexp(cost, &exponent);  // cost = mantissa · 2^exponent, mantissa in [0.5, 1)
    const int quarter = std::min(3, static_cast<int>((mantissa - 0.5) * 8));
    return static_cast<std::size_t>(std::clamp(4 * (exponent + 1100) + quarter, 0, 4 * 2200));
  }
  std::vector<std::vector<Candidate>> buckets_;
  std::size_t lowest_ = std::numeric_limits<std::size_t>::max();
  std::size_t size_ = 0;
};

class Coarsener {
 public:
  Coarsener(const Vertices& V, const Faces& F) : mesh_(to_halfedge_mesh(Mesh{V, F})) {
    mesh_.request_vertex_status();
    mesh_.request_edge_status();
    mesh_.request_face_status();
    version_.assign(mesh_.n_edges(), 0);
    valence_.resize(mesh_.n_vertices());
    for (const auto v : mesh_.vertices())
      valence_[static_cast<std::size_t>(v.idx())] = static_cast<int>(mesh_.valence(v));
    for (const auto e : mesh_.edges()) push(e);
  }

  ProgressiveMesh run(const JobControl* control, const std::function<void(double)>& progress) {
    ProgressiveMesh pm;
    std::size_t alive = mesh_.n_vertices();
    pm.removed.reserve(alive);
    pm.kept.reserve(alive);
    pm.ring.reserve(6 * alive);
    bool collapsed_since_refill = true;
    while (alive > 4) {
      if (queue_.empty()) {  // collapses refused earlier may be safe now
        if (!collapsed_since_refill)
          throw std::logic_error("coarsening stalled: no edge of the mesh can be collapsed safely");
        refill();
        collapsed_since_refill = false;
      }
      const Candidate c = queue_.pop();
      const auto e = mesh_.edge_handle(c.edge);
      if (c.version != version_[c.edge] || mesh_.status(e).deleted()) continue;
      if (!collapse(e, pm)) continue;
      collapsed_since_refill = true;
      --alive;
      if (alive % 1024 == 0) {
        poll(control);
        if (progress) progress(1.0 - static_cast<double>(alive) / static_cast<double>(mesh_.n_vertices()));
      }
    }
    record_base(pm);
    return pm;
  }

 private:
  // Short edges first, and of those the ones whose collapse leaves a low valence: a vertex that
  // swallowed many neighbours would make every later collapse around it slower, and its
  // re-inserted neighbours crowd into thin wedges on the sphere.
  double cost(HalfedgeMesh::EdgeHandle e) const {
    const auto h = mesh_.halfedge_handle(e, 0);
    const auto a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const double length2 = (mesh_.point(b) - mesh_.point(a)).sqrnorm();
    const double merged =
        static_cast<double>(valence_[static_cast<std::size_t>(a.idx())] + valence_[static_cast<std::size_t>(b.idx())]) -
        4;
    const double crowding = std::max(1.0, merged / 6);
    return length2 * crowding * crowding;
  }

  void push(HalfedgeMesh::EdgeHandle e) { queue_.push(cost(e), {e.idx(), ++version_[e.idx()]}); }

  void refill() {
    for (const auto e : mesh_.edges())
      if (!mesh_.status(e).deleted()) push(e);
  }

  int valence(HalfedgeMesh::VertexHandle v) const { return valence_[static_cast<std::size_t>(v.idx())]; }

  // The rule of core/mesh/collapse_is_safe with valences kept up to date here (OpenMesh counts
  // them by walking around the vertex, a third of the time): the link condition, and no vertex
  // left with fewer than three neighbours. On a closed surface both directions are alike.
  bool safe(HalfedgeMesh::HalfedgeHandle h) {
    if (valence(mesh_.from_vertex_handle(h)) + valence(mesh_.to_vertex_handle(h)) - 4 < 3) return false;
    for (const auto side : {h, mesh_.opposite_halfedge_handle(h)})
      if (valence(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(side))) <= 3) return false;
    return mesh_.is_collapse_ok(h);
  }

  // Collapses e (its endpoint with the lower index survives: a fixed rule keeps the sequence
  // deterministic); records the removed vertex's ring.
  bool collapse(HalfedgeMesh::EdgeHandle e, ProgressiveMesh& pm) {
    HalfedgeMesh::HalfedgeHandle h = mesh_.halfedge_handle(e, 0);
    if (mesh_.to_vertex_handle(h).idx() > mesh_.from_vertex_handle(h).idx()) h = mesh_.opposite_halfedge_handle(h);
    if (!safe(h)) return false;
    const auto gone = mesh_.from_vertex_handle(h), kept = mesh_.to_vertex_handle(h);
    // The two corners of the edge's faces lose their edge to `gone`; `kept` takes its others.
    for (const auto side : {h, mesh_.opposite_halfedge_handle(h)})
      --valence_[static_cast<std::size_t>(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(side)).idx())];
    valence_[static_cast<std::size_t>(kept.idx())] += valence(gone) - 4;
    // The ring, counter-clockwise from `kept`: rotate the outgoing halfedge.
    auto around = h;
    do {
      pm.ring.push_back(mesh_.to_vertex_handle(around).idx());
      around = mesh_.opposite_halfedge_handle(mesh_.prev_halfedge_handle(around));
    } while (around != h);
    pm.ring_offsets.push_back(static_cast<int>(pm.ring.size()));
    pm.removed.push_back(gone.idx());
    pm.kept.push_back(kept.idx());
    mesh_.collapse(h);
    // The edges around `kept` changed their cost; edges refused before come back with the next
    // refill.
    for (const auto ke : mesh_.ve_range(kept)) push(ke);
    return true;
  }

  void record_base(ProgressiveMesh& pm) {
    int k = 0;
    for (const auto v : mesh_.vertices())
      if (!mesh_.status(v).deleted()) pm.base_vertices[static_cast<std::size_t>(k++)] = v.idx();
    pm.base_faces.resize(4, 3);
    int f = 0;
    for (const auto face : mesh_.faces()) {
      if (mesh_.status(face).deleted()) continue;
      int c = 0;
      for (const auto v : mesh_.fv_range(face)) pm.base_faces(f, c++) = v.idx();
      ++f;
    }
    if (k != 4 || f != 4) throw std::logic_error("coarsening did not end in a tetrahedron");
  }

  HalfedgeMesh mesh_;
  std::vector<int> version_;
  std::vector<int> valence_;
  BucketQueue queue_;
};

}  // namespace

ProgressiveMesh coarsen_to_tetrahedron(const Vertices& V, const Faces& F, const JobControl* control,
                                       const std::function<void(double)>& progress) {
  if (V.rows() < 4) throw std::invalid_argument("a closed surface needs at least 4 vertices");
  return Coarsener(V, F).run(control, progress);
}

std::vector<int> insertion_order(const ProgressiveMesh& pm) {
  std::vector<int> order(pm.base_vertices.begin(), pm.base_vertices.end());
  order.reserve(4 + pm.collapses());
  for (std::size_t i = pm.collapses(); i-- > 0;) order.push_back(pm.removed[i]);
  return order;
}

}  // namespace meshmark
