#include "core/mesh/openmesh_convert.hpp"

#include "core/mesh/cut_to_manifold.hpp"

#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>

namespace meshmark {

HalfedgeMesh to_halfedge_mesh(const Mesh& input, NonManifoldFaces non_manifold) {
  const bool detach = non_manifold == NonManifoldFaces::detach;
  std::optional<ManifoldPieces> pieces;
  if (detach) pieces = cut_to_manifold(input);
  const Mesh& mesh = detach ? pieces->mesh : input;
  HalfedgeMesh out;
  out.reserve(static_cast<std::size_t>(mesh.V.rows()), static_cast<std::size_t>(3 * mesh.F.rows()),
              static_cast<std::size_t>(mesh.F.rows()));
  std::vector<HalfedgeMesh::VertexHandle> handles;
  handles.reserve(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    handles.push_back(out.add_vertex(HalfedgeMesh::Point(mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2))));
  // A refused face is ours to report or to detach: OpenMesh's own complaint on stderr is noise.
  omerr().disable();
  struct Reenable {
    ~Reenable() { omerr().enable(); }
  } reenable;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    // OpenMesh asserts (not reports) on these: refuse them first.
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= mesh.V.rows())
      throw std::invalid_argument("face " + std::to_string(f) + " refers to a vertex that does not exist");
    if (a == b || b == c || a == c) {
      if (detach) continue;
      throw std::invalid_argument("face " + std::to_string(f) + " repeats a vertex; it cannot be processed");
    }
    auto face = out.add_face(handles[a], handles[b], handles[c]);
    if (!face.is_valid() && detach) {
      std::array<HalfedgeMesh::VertexHandle, 3> own;
      for (int k = 0; k < 3; ++k) own[k] = out.add_vertex(out.point(handles[mesh.F(f, k)]));
      face = out.add_face(own[0], own[1], own[2]);
    }
    if (!face.is_valid())
      throw std::invalid_argument("face " + std::to_string(f) + " makes the mesh non-manifold; it cannot be processed");
  }
  return out;
}

Mesh from_halfedge_mesh(HalfedgeMesh& mesh) {
  mesh.garbage_collection();
  Mesh out;
  out.V.resize(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    out.V.row(v.idx()) << p[0], p[1], p[2];
  }
  out.F.resize(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (const auto f : mesh.faces()) {
    int k = 0;
    for (const auto v : mesh.fv_range(f)) out.F(f.idx(), k++) = v.idx();
  }
  return out;
}

}  // namespace meshmark
