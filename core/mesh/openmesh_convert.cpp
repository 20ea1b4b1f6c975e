#include "core/mesh/openmesh_convert.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace meshmark {

HalfedgeMesh to_halfedge_mesh(const Mesh& mesh) {
  HalfedgeMesh out;
  out.reserve(static_cast<std::size_t>(mesh.V.rows()), static_cast<std::size_t>(3 * mesh.F.rows()),
              static_cast<std::size_t>(mesh.F.rows()));
  std::vector<HalfedgeMesh::VertexHandle> handles;
  handles.reserve(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    handles.push_back(out.add_vertex(HalfedgeMesh::Point(mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2))));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    // OpenMesh asserts (not reports) on these: refuse them first.
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= mesh.V.rows())
      throw std::invalid_argument("face " + std::to_string(f) + " refers to a vertex that does not exist");
    if (a == b || b == c || a == c)
      throw std::invalid_argument("face " + std::to_string(f) + " repeats a vertex; it cannot be processed");
    const auto face = out.add_face(handles[a], handles[b], handles[c]);
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
