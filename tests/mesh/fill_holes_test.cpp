#include "core/mesh/fill_holes.hpp"

#include <gtest/gtest.h>

#include "core/mesh/validate_mesh.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(FillHoles, ThreeHolesCloseIntoOneGenusZeroSurface) {
  const Mesh& holes = test::procedural_mesh("creature_holes");
  const FilledHoles filled = fill_holes(holes);
  EXPECT_EQ(filled.holes, 3u);
  const MeshReport r = validate_mesh(filled.mesh);
  EXPECT_TRUE(r.closed_genus_zero) << (r.sphere_problems.empty() ? "" : r.sphere_problems.front());
}

TEST(FillHoles, TheOriginalComesFirstAndUnchanged) {
  const Mesh& holes = test::procedural_mesh("creature_holes");
  const FilledHoles filled = fill_holes(holes);
  ASSERT_EQ(filled.original_vertices, holes.V.rows());
  ASSERT_EQ(filled.original_faces, holes.F.rows());
  EXPECT_TRUE(filled.mesh.V.topRows(holes.V.rows()) == holes.V);
  EXPECT_TRUE(filled.mesh.F.topRows(holes.F.rows()) == holes.F);
  EXPECT_EQ(filled.mesh.V.rows(), holes.V.rows() + 3);  // one centre per hole
}

TEST(FillHoles, AClosedMeshGetsNothing) {
  const Mesh& closed = test::procedural_mesh("creature");
  const FilledHoles filled = fill_holes(closed);
  EXPECT_EQ(filled.holes, 0u);
  EXPECT_TRUE(filled.mesh.V == closed.V && filled.mesh.F == closed.F);
}

}  // namespace
}  // namespace meshmark
