#include "core/attacks/subdivide.hpp"

#include <gtest/gtest.h>

#include "core/mesh/validate_mesh.hpp"
#include "core/spatial/aabb_tree.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(Subdivide, EachStepQuadruplesTheFacesAndKeepsTheTopology) {
  const Mesh& spot = test::load_shared("spot.obj");
  for (auto scheme : {SubdivisionScheme::midpoint, SubdivisionScheme::loop}) {
    const Mesh out = subdivide(spot, scheme, 2);
    EXPECT_EQ(out.F.rows(), 16 * spot.F.rows()) << to_string(scheme);
    const MeshReport r = validate_mesh(out);
    EXPECT_TRUE(r.closed_genus_zero) << to_string(scheme);
    EXPECT_EQ(r.genus, 0);
  }
}

TEST(Subdivide, Sqrt3TriplesTheFaces) {
  const Mesh& spot = test::load_shared("spot.obj");
  const Mesh out = subdivide(spot, SubdivisionScheme::sqrt3, 1);
  EXPECT_EQ(out.F.rows(), 3 * spot.F.rows());
  EXPECT_EQ(out.V.rows(), spot.V.rows() + spot.F.rows());
  EXPECT_TRUE(validate_mesh(out).closed_genus_zero);
}

TEST(Subdivide, MidpointKeepsTheSurfaceAndTheOriginalVertices) {
  const Mesh& spot = test::load_shared("spot.obj");
  const Mesh out = subdivide(spot, SubdivisionScheme::midpoint, 1);
  EXPECT_TRUE(out.V.topRows(spot.V.rows()) == spot.V);
  const AabbTree tree(spot.V, spot.F);
  for (Eigen::Index v = spot.V.rows(); v < out.V.rows(); v += 13)
    EXPECT_LT(tree.closest_point(out.V.row(v).transpose())->distance_squared, 1e-24);
}

TEST(Subdivide, LoopSmoothsTheOriginalVertices) {
  const Mesh& spot = test::load_shared("spot.obj");
  const Mesh out = subdivide(spot, SubdivisionScheme::loop, 1);
  EXPECT_GT((out.V.topRows(spot.V.rows()) - spot.V).norm(), 0.0);
}

TEST(Subdivide, UnknownSchemeIsRefused) { EXPECT_THROW(parse_subdivision_scheme("catmull"), std::invalid_argument); }

}  // namespace
}  // namespace meshmark
