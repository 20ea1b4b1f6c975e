#include "core/attacks/subdivide.hpp"

#include <gtest/gtest.h>

#include "core/mesh/validate_mesh.hpp"
#include "core/spatial/aabb_tree.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(Subdivide, EachStepQuadruplesTheFacesAndKeepsTheTopology) {
  const Mesh& creature = test::procedural_mesh("creature");
  for (auto scheme : {SubdivisionScheme::midpoint, SubdivisionScheme::loop}) {
    const Mesh out = subdivide(creature, scheme, 2);
    EXPECT_EQ(out.F.rows(), 16 * creature.F.rows()) << to_string(scheme);
    const MeshReport r = validate_mesh(out);
    EXPECT_TRUE(r.closed_genus_zero) << to_string(scheme);
    EXPECT_EQ(r.genus, 0);
  }
}

TEST(Subdivide, Sqrt3TriplesTheFaces) {
  const Mesh& creature = test::procedural_mesh("creature");
  const Mesh out = subdivide(creature, SubdivisionScheme::sqrt3, 1);
  EXPECT_EQ(out.F.rows(), 3 * creature.F.rows());
  EXPECT_EQ(out.V.rows(), creature.V.rows() + creature.F.rows());
  EXPECT_TRUE(validate_mesh(out).closed_genus_zero);
}

TEST(Subdivide, MidpointKeepsTheSurfaceAndTheOriginalVertices) {
  const Mesh& creature = test::procedural_mesh("creature");
  const Mesh out = subdivide(creature, SubdivisionScheme::midpoint, 1);
  EXPECT_TRUE(out.V.topRows(creature.V.rows()) == creature.V);
  const AabbTree tree(creature.V, creature.F);
  for (Eigen::Index v = creature.V.rows(); v < out.V.rows(); v += 13)
    EXPECT_LT(tree.closest_point(out.V.row(v).transpose())->distance_squared, 1e-24);
}

TEST(Subdivide, LoopSmoothsTheOriginalVertices) {
  const Mesh& creature = test::procedural_mesh("creature");
  const Mesh out = subdivide(creature, SubdivisionScheme::loop, 1);
  EXPECT_GT((out.V.topRows(creature.V.rows()) - creature.V).norm(), 0.0);
}

TEST(Subdivide, UnknownSchemeIsRefused) { EXPECT_THROW(parse_subdivision_scheme("catmull"), std::invalid_argument); }

}  // namespace
}  // namespace meshmark
