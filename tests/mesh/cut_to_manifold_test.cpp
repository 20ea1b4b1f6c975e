#include "core/mesh/cut_to_manifold.hpp"

#include <gtest/gtest.h>

#include "core/mesh/validate_mesh.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(CutToManifold, AManifoldMeshIsLeftAsItIs) {
  const Mesh& creature = test::procedural_mesh("creature");
  const ManifoldPieces p = cut_to_manifold(creature);
  EXPECT_TRUE(p.mesh.V == creature.V);
  EXPECT_TRUE(p.mesh.F == creature.F);
}

TEST(CutToManifold, APinchVertexGetsOneCopyAndNothingElseChanges) {
  const Mesh& pinched = test::procedural_mesh("pinched");
  const ManifoldPieces p = cut_to_manifold(pinched);
  EXPECT_EQ(p.mesh.V.rows(), pinched.V.rows() + 1);
  EXPECT_EQ(p.origin.back(), validate_mesh(pinched).nonmanifold_vertex_examples.at(0));
  const MeshReport r = validate_mesh(p.mesh);
  EXPECT_EQ(r.nonmanifold_vertices, 0u);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
  EXPECT_TRUE(p.mesh.V.topRows(pinched.V.rows()) == pinched.V);
}

TEST(CutToManifold, AFinOnAnEdgeComesOffAsItsOwnPiece) {
  Mesh mesh = test::cube();
  mesh.V.conservativeResize(9, 3);
  mesh.V.row(8) << 0.5, 0.5, -1;
  mesh.F.conservativeResize(13, 3);
  mesh.F.row(12) << 0, 1, 8;
  const ManifoldPieces p = cut_to_manifold(mesh);
  const MeshReport r = validate_mesh(p.mesh);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
  EXPECT_EQ(r.nonmanifold_vertices, 0u);
  for (std::size_t v = 0; v < p.origin.size(); ++v)
    EXPECT_TRUE(p.mesh.V.row(static_cast<Eigen::Index>(v)) == mesh.V.row(p.origin[v]));
}

TEST(CutToManifold, FacesThatRepeatAVertexAreDroppedAndCounted) {
  Mesh mesh = test::cube();
  mesh.F.conservativeResize(13, 3);
  mesh.F.row(12) << 0, 0, 1;
  const ManifoldPieces p = cut_to_manifold(mesh);
  EXPECT_EQ(p.dropped_faces, 1u);
  EXPECT_EQ(p.mesh.F.rows(), 12);
}

}  // namespace
}  // namespace meshmark
