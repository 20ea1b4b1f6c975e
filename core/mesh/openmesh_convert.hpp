#pragma once
// Conversions between our Eigen meshes and OpenMesh's halfedge mesh, for the algorithms we take
// from OpenMesh (decimation, subdivision). Vertex and face order are kept.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct OpenMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using HalfedgeMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMeshTraits>;

/// Builds a halfedge mesh. Throws std::invalid_argument if OpenMesh refuses a face (a
/// non-manifold configuration) rather than silently dropping it.
HalfedgeMesh to_halfedge_mesh(const Mesh& mesh);

/// Reads back vertices and faces (after garbage collection, in OpenMesh's order).
Mesh from_halfedge_mesh(HalfedgeMesh& mesh);

}  // namespace meshmark
