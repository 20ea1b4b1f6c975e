#include "core/mesh/weld_positions.hpp"

#include <gtest/gtest.h>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// Each side of a double-sided sheet stored with its own vertices, as exporters write them.
Mesh with_separate_back_vertices(const Mesh& two_sided, Eigen::Index front_faces) {
  Mesh out;
  out.V.resize(two_sided.V.rows() * 2, 3);
  out.V << two_sided.V, two_sided.V;
  out.F = two_sided.F;
  out.F.bottomRows(two_sided.F.rows() - front_faces).array() += static_cast<int>(two_sided.V.rows());
  return out;
}

TEST(WeldPositions, TheBackOfADoubleSidedSurfaceIsLeftOutAndItsVerticesJoinTheFront) {
  const Mesh& creature = test::procedural_mesh("creature");
  const Mesh stored = with_separate_back_vertices(double_sided(creature), creature.F.rows());
  const WeldedSurface s = weld_positions(stored.V, stored.F);
  EXPECT_TRUE(s.mesh.V == creature.V);
  EXPECT_TRUE(s.mesh.F == creature.F) << "the front, in its stored winding, is the surface";
  EXPECT_EQ(s.duplicate_triangles, static_cast<std::size_t>(creature.F.rows()));
  EXPECT_EQ(s.welded_copies, static_cast<std::size_t>(creature.V.rows()));
  ASSERT_EQ(s.face_of.size(), static_cast<std::size_t>(creature.F.rows()));
  for (std::size_t f = 0; f < s.face_of.size(); ++f) EXPECT_EQ(s.face_of[f], static_cast<int>(f));
  // Both sides' stored vertices follow the surface.
  const Vertices moved = creature.V.array() + 1.0;
  const Vertices stored_moved = stored_positions(s, moved, stored.V);
  EXPECT_TRUE(stored_moved.topRows(creature.V.rows()) == moved);
  EXPECT_TRUE(stored_moved.bottomRows(creature.V.rows()) == moved);
}

TEST(WeldPositions, AFaceStoredTwiceInTheSameWindingIsKeptOnce) {
  const Mesh& creature = test::procedural_mesh("creature_small");
  Faces twice(creature.F.rows() + 2, 3);
  twice << creature.F, creature.F.row(5), creature.F.row(7).reverse();
  const WeldedSurface s = weld_positions(creature.V, twice);
  EXPECT_EQ(s.duplicate_triangles, 2u);
  EXPECT_TRUE(s.mesh.F == creature.F);
}

// A triangle soup (every corner stored on its own, as STL stores it) welds back to the mesh it came
// from: one surface vertex per position, the first stored copy naming it, −0 and +0 alike.
TEST(WeldPositions, ATriangleSoupWeldsBackToItsMeshVertexForVertex) {
  Mesh mesh = test::procedural_mesh("creature");
  mesh.V(0, 0) = 0.0;
  Mesh soup{Vertices(3 * mesh.F.rows(), 3), Faces(mesh.F.rows(), 3)};
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      soup.V.row(3 * f + k) = mesh.V.row(mesh.F(f, k));
      if (mesh.F(f, k) == 0 && f % 2 == 1) soup.V(3 * f + k, 0) = -0.0;
      soup.F(f, k) = static_cast<int>(3 * f + k);
    }
  const WeldedSurface s = weld_positions(soup.V, soup.F);
  ASSERT_EQ(s.mesh.V.rows(), mesh.V.rows());
  ASSERT_EQ(s.mesh.F.rows(), mesh.F.rows());
  EXPECT_EQ(s.welded_copies, static_cast<std::size_t>(soup.V.rows() - mesh.V.rows()));
  std::vector<int> surface_vertex(static_cast<std::size_t>(mesh.V.rows()), -1);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int welded = s.vertex_of[static_cast<std::size_t>(3 * f + k)];
      int& seen = surface_vertex[static_cast<std::size_t>(mesh.F(f, k))];
      if (seen < 0) seen = welded;
      EXPECT_EQ(welded, seen) << "corner " << k << " of face " << f;
      EXPECT_TRUE((s.mesh.V.row(welded).array() == mesh.V.row(mesh.F(f, k)).array()).all());
      EXPECT_EQ(s.mesh.F(f, k), welded);
    }
}

TEST(WeldPositions, FacesSharingTwoVerticesAreNotDuplicates) {
  const Mesh& creature = test::procedural_mesh("creature_small");
  const WeldedSurface s = weld_positions(creature.V, creature.F);
  EXPECT_EQ(s.duplicate_triangles, 0u);
  EXPECT_EQ(s.mesh.F.rows(), creature.F.rows());
}

}  // namespace
}  // namespace meshmark
