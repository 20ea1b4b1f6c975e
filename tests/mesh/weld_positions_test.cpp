#include "core/mesh/weld_positions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

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

// The faces kept are the first of each vertex set, whatever the set's smallest vertex is shared by
// a handful of triangles (compared pairwise) or by many (a hub's fan, sorted): checked against every
// earlier face, on random triangles over 30 and over 3,000 distinct vertices.
TEST(WeldPositions, EachVertexSetIsKeptOnceAtItsFirstTriangleInSmallAndLargeBuckets) {
  for (const int vertices : {30, 3000}) {
    std::mt19937 random(static_cast<unsigned>(vertices));
    std::uniform_int_distribution<int> vertex(0, vertices - 1);
    Vertices V(vertices, 3);
    for (int v = 0; v < vertices; ++v) V.row(v) << v, v * v, 1.0;
    Faces F(4000, 3);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      do F.row(f) << vertex(random), vertex(random), vertex(random);
      while (F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 0) == F(f, 2));
      if (f > 0 && f % 3 == 0) F.row(f) = F.row(random() % f).reverse();  // a repeat, in the other winding
    }
    std::vector<int> first_of_its_set;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const auto set = [&](Eigen::Index g) {
        std::array<int, 3> c{F(g, 0), F(g, 1), F(g, 2)};
        std::sort(c.begin(), c.end());
        return c;
      };
      bool repeat = false;
      for (Eigen::Index g = 0; g < f && !repeat; ++g) repeat = set(g) == set(f);
      if (!repeat) first_of_its_set.push_back(static_cast<int>(f));
    }
    const WeldedSurface s = weld_positions(V, F);
    EXPECT_EQ(s.face_of, first_of_its_set) << vertices << " vertices";
    EXPECT_EQ(s.duplicate_triangles, static_cast<std::size_t>(F.rows()) - first_of_its_set.size());
  }
}

}  // namespace
}  // namespace meshmark
