#include "core/mesh/collapse_is_safe.hpp"

namespace meshmark {

namespace {

// The valence a vertex keeps after the collapse, given how many of its edges merge away.
bool keeps_three(const HalfedgeMesh& mesh, HalfedgeMesh::VertexHandle v, int lost) {
  if (mesh.is_boundary(v)) return true;
  return static_cast<int>(mesh.valence(v)) - lost >= 3;
}

}  // namespace

bool collapse_is_safe(HalfedgeMesh& mesh, HalfedgeMesh::HalfedgeHandle h) {
  if (!mesh.is_collapse_ok(h)) return false;
  const auto from = mesh.from_vertex_handle(h), to = mesh.to_vertex_handle(h);
  // The far corner of each face on the edge loses its edge to `from`.
  for (const auto side : {h, mesh.opposite_halfedge_handle(h)}) {
    if (mesh.is_boundary(side)) continue;
    const auto corner = mesh.to_vertex_handle(mesh.next_halfedge_handle(side));
    if (!keeps_three(mesh, corner, 1)) return false;
  }
  // The merged vertex has the neighbours of both, less the edge itself and the shared corners.
  const int faces_on_edge =
      (mesh.is_boundary(h) ? 0 : 1) + (mesh.is_boundary(mesh.opposite_halfedge_handle(h)) ? 0 : 1);
  const int merged = static_cast<int>(mesh.valence(from) + mesh.valence(to)) - 2 - faces_on_edge;
  return mesh.is_boundary(from) || mesh.is_boundary(to) || merged >= 3;
}

}  // namespace meshmark
