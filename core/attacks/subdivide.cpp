#include "core/attacks/subdivide.hpp"

#include <stdexcept>

#include "core/mesh/edge_incidence.hpp"
#include "core/mesh/openmesh_convert.hpp"
// OpenMesh's subdividers only compile after its mesh kernel headers.
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/Sqrt3T.hh>

namespace meshmark {

std::string to_string(SubdivisionScheme scheme) {
  switch (scheme) {
    case SubdivisionScheme::midpoint:
      return "midpoint";
    case SubdivisionScheme::loop:
      return "loop";
    case SubdivisionScheme::sqrt3:
      return "sqrt3";
  }
  return "midpoint";
}

SubdivisionScheme parse_subdivision_scheme(const std::string& name) {
  for (auto s : {SubdivisionScheme::midpoint, SubdivisionScheme::loop, SubdivisionScheme::sqrt3})
    if (name == to_string(s)) return s;
  throw std::invalid_argument("unknown subdivision scheme '" + name + "' (expected midpoint, loop or sqrt3)");
}

namespace {

Mesh midpoint_once(const Mesh& mesh) {
  const EdgeIncidence inc = edge_incidence(mesh.F);
  const Eigen::Index nv = mesh.V.rows(), ne = inc.edges.rows();
  Mesh out;
  out.V.resize(nv + ne, 3);
  out.V.topRows(nv) = mesh.V;
  for (Eigen::Index e = 0; e < ne; ++e)
    out.V.row(nv + e) = 0.5 * (mesh.V.row(inc.edges(e, 0)) + mesh.V.row(inc.edges(e, 1)));
  out.F.resize(4 * mesh.F.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    const int ab = static_cast<int>(nv + inc.face_edges(f, 0)), bc = static_cast<int>(nv + inc.face_edges(f, 1)),
              ca = static_cast<int>(nv + inc.face_edges(f, 2));
    out.F.row(4 * f) << a, ab, ca;
    out.F.row(4 * f + 1) << ab, b, bc;
    out.F.row(4 * f + 2) << ca, bc, c;
    out.F.row(4 * f + 3) << ab, bc, ca;
  }
  return out;
}

template <typename Subdivider>
Mesh openmesh_subdivide(const Mesh& mesh, int steps) {
  HalfedgeMesh hm = to_halfedge_mesh(mesh, NonManifoldFaces::detach);
  Subdivider subdivider;
  subdivider.attach(hm);
  subdivider(static_cast<std::size_t>(steps));
  subdivider.detach();
  return from_halfedge_mesh(hm);
}

}  // namespace

Mesh subdivide(const Mesh& mesh, SubdivisionScheme scheme, int steps) {
  if (steps < 0) throw std::invalid_argument("subdivision steps must be at least 0");
  switch (scheme) {
    case SubdivisionScheme::midpoint: {
      Mesh out = mesh;
      for (int s = 0; s < steps; ++s) out = midpoint_once(out);
      return out;
    }
    case SubdivisionScheme::loop:
      return openmesh_subdivide<OpenMesh::Subdivider::Uniform::LoopT<HalfedgeMesh>>(mesh, steps);
    case SubdivisionScheme::sqrt3:
      return openmesh_subdivide<OpenMesh::Subdivider::Uniform::Sqrt3T<HalfedgeMesh>>(mesh, steps);
  }
  return mesh;
}

}  // namespace meshmark
