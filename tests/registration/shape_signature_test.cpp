#include "core/registration/shape_signature.hpp"

#include <gtest/gtest.h>

#include "core/attacks/reorder.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/attacks/simplify.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// A copy moved, turned, scaled, reordered, or simplified to a quarter stays far closer to its
// original than another shape does: what lets a search short-list the right original. (The same
// outline with holes cut in it stays close too, as a search wants.)
TEST(ShapeSignature, ACopyInAnyPoseIsCloserToItsOriginalThanOtherShapesAre) {
  const Mesh& creature = test::procedural_mesh("creature");
  const ShapeSignature original = shape_signature(creature);
  EXPECT_EQ(signature_distance(original, original), 0.0);
  const Mesh moved = reorder(transform_mesh(creature, random_similarity(creature, 3)), 5);
  const Mesh quarter = simplify(moved, 0.25);
  const double to_moved = signature_distance(original, shape_signature(moved));
  const double to_quarter = signature_distance(original, shape_signature(quarter));
  EXPECT_LT(to_moved, 0.02);
  EXPECT_LT(to_quarter, 0.1);
  for (const char* other : {"torus", "creature_small", "parts"}) {
    const double apart = signature_distance(original, shape_signature(test::procedural_mesh(other)));
    EXPECT_GT(apart, 3 * to_quarter) << other;
  }
  Mesh stretched = creature;
  stretched.V.col(0) *= 1.3;  // the same outline, 30 % longer one way
  EXPECT_GT(signature_distance(original, shape_signature(stretched)), 3 * to_quarter);
}

TEST(ShapeSignature, ItsValuesRoundTripAndAWrongLengthIsRefused) {
  const ShapeSignature s = shape_signature(test::procedural_mesh("torus"));
  const std::vector<double> values = signature_values(s);
  ASSERT_EQ(values.size(), static_cast<std::size_t>(kSignatureBins + 2));
  EXPECT_EQ(signature_distance(signature_from_values(values), s), 0.0);
  EXPECT_THROW(signature_from_values({1.0, 2.0}), std::invalid_argument);
  double total = 0;
  for (const double share : s.distances) total += share;
  EXPECT_NEAR(total, 1.0, 1e-9) << "every pair in one bin";
}

}  // namespace
}  // namespace meshmark
