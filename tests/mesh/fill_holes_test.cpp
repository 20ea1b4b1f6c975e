#include "core/mesh/fill_holes.hpp"

#include <gtest/gtest.h>

#include "core/mesh/validate_mesh.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(FillHoles, TheBunnysFiveHolesCloseIntoOneGenusZeroSurface) {
  const Mesh& holes = test::load_shared("bunny_holes.off");
  const FilledHoles filled = fill_holes(holes);
  EXPECT_EQ(filled.holes, 5u);
  const MeshReport r = validate_mesh(filled.mesh);
  EXPECT_TRUE(r.closed_genus_zero) << (r.sphere_problems.empty() ? "" : r.sphere_problems.front());
}

TEST(FillHoles, TheOriginalComesFirstAndUnchanged) {
  const Mesh& holes = test::load_shared("bunny_holes.off");
  const FilledHoles filled = fill_holes(holes);
  ASSERT_EQ(filled.original_vertices, holes.V.rows());
  ASSERT_EQ(filled.original_faces, holes.F.rows());
  EXPECT_TRUE(filled.mesh.V.topRows(holes.V.rows()) == holes.V);
  EXPECT_TRUE(filled.mesh.F.topRows(holes.F.rows()) == holes.F);
  EXPECT_EQ(filled.mesh.V.rows(), holes.V.rows() + 5);  // one centre per hole
}

TEST(FillHoles, AClosedMeshGetsNothing) {
  const Mesh& spot = test::load_shared("spot.obj");
  const FilledHoles filled = fill_holes(spot);
  EXPECT_EQ(filled.holes, 0u);
  EXPECT_TRUE(filled.mesh.V == spot.V && filled.mesh.F == spot.F);
}

}  // namespace
}  // namespace meshmark
