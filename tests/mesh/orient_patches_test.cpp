#include "core/mesh/orient_patches.hpp"

#include <gtest/gtest.h>

#include "core/mesh/orientation.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(OrientPatches, FlippedFacesOfAClosedSurfaceAreTurnedBackOutward) {
  const Mesh& creature = test::procedural_mesh("creature");
  Faces scrambled = creature.F;
  for (Eigen::Index f = 0; f < scrambled.rows(); f += 3) std::swap(scrambled(f, 1), scrambled(f, 2));
  const OrientedPatches p = orient_patches(creature.V, scrambled);
  EXPECT_EQ(p.patches, 1u);
  EXPECT_TRUE(p.faces == creature.F);
  EXPECT_EQ(p.reversed, static_cast<std::size_t>((scrambled.rows() + 2) / 3));
}

TEST(OrientPatches, AnInwardClosedSurfaceIsTurnedOutward) {
  const Mesh& creature = test::procedural_mesh("creature");
  Faces inward = creature.F;
  inward.col(1).swap(inward.col(2));
  EXPECT_TRUE(orient_patches(creature.V, inward).faces == creature.F);
}

TEST(OrientPatches, TheInputFacesAreNeverChangedOnlyCopied) {
  const Mesh& pinched = test::procedural_mesh("pinched");
  const Faces before = pinched.F;
  const OrientedPatches p = orient_patches(pinched.V, pinched.F);
  EXPECT_TRUE(pinched.F == before);
  ASSERT_EQ(p.faces.rows(), pinched.F.rows());
  for (Eigen::Index f = 0; f < pinched.F.rows(); ++f) {  // each face is itself or its reverse
    const bool same = p.faces.row(f) == pinched.F.row(f);
    const bool reversed =
        p.faces(f, 0) == pinched.F(f, 0) && p.faces(f, 1) == pinched.F(f, 2) && p.faces(f, 2) == pinched.F(f, 1);
    EXPECT_TRUE(same || reversed) << f;
  }
}

}  // namespace
}  // namespace meshmark
