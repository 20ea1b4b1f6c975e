#include "core/mesh/orient_patches.hpp"

#include <gtest/gtest.h>

#include "core/mesh/orientation.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(OrientPatches, FlippedFacesOfAClosedSurfaceAreTurnedBackOutward) {
  const Mesh& spot = test::load_shared("spot.obj");
  Faces scrambled = spot.F;
  for (Eigen::Index f = 0; f < scrambled.rows(); f += 3) std::swap(scrambled(f, 1), scrambled(f, 2));
  const OrientedPatches p = orient_patches(spot.V, scrambled);
  EXPECT_EQ(p.patches, 1u);
  EXPECT_TRUE(p.faces == spot.F);
  EXPECT_EQ(p.reversed, static_cast<std::size_t>((scrambled.rows() + 2) / 3));
}

TEST(OrientPatches, AnInwardClosedSurfaceIsTurnedOutward) {
  const Mesh& spot = test::load_shared("spot.obj");
  Faces inward = spot.F;
  inward.col(1).swap(inward.col(2));
  EXPECT_TRUE(orient_patches(spot.V, inward).faces == spot.F);
}

TEST(OrientPatches, TheInputFacesAreNeverChangedOnlyCopied) {
  const Mesh& cow = test::load_shared("cow_nonmanifold.obj");
  const Faces before = cow.F;
  const OrientedPatches p = orient_patches(cow.V, cow.F);
  EXPECT_TRUE(cow.F == before);
  ASSERT_EQ(p.faces.rows(), cow.F.rows());
  for (Eigen::Index f = 0; f < cow.F.rows(); ++f) {  // each face is itself or its reverse
    const bool same = p.faces.row(f) == cow.F.row(f);
    const bool reversed = p.faces(f, 0) == cow.F(f, 0) && p.faces(f, 1) == cow.F(f, 2) && p.faces(f, 2) == cow.F(f, 1);
    EXPECT_TRUE(same || reversed) << f;
  }
}

}  // namespace
}  // namespace meshmark
