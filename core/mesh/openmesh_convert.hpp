#pragma once
// Conversions between our Eigen meshes and OpenMesh's halfedge mesh, for OpenMesh's subdivision
// schemes and for our own halfedge algorithms (simplification, remeshing, the progressive mesh)
// on its connectivity. Vertex and face order are kept.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct OpenMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using HalfedgeMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMeshTraits>;

/// What to do with a face a halfedge mesh cannot hold (a non-manifold edge or pinch).
enum class NonManifoldFaces {
  refuse,  ///< throw std::invalid_argument, naming the face
  detach,  ///< cut the mesh into manifold pieces first (cut_to_manifold.hpp), then give any face
           ///< still refused its own corners: for attacks, which may change connectivity
};

/// Builds a halfedge mesh: with `refuse`, vertices and faces in order; with `detach`, the
/// input's vertices first, their copies after, and faces that repeat a vertex dropped.
HalfedgeMesh to_halfedge_mesh(const Mesh& input, NonManifoldFaces non_manifold = NonManifoldFaces::refuse);

/// Reads back vertices and faces (after garbage collection, in OpenMesh's order).
Mesh from_halfedge_mesh(HalfedgeMesh& mesh);

}  // namespace meshmark
