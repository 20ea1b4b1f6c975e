#include "core/registration/same_surface.hpp"

#include <gtest/gtest.h>

#include "core/attacks/reorder.hpp"
#include "core/attacks/round_digits.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "tests/procedural_meshes.hpp"

namespace meshmark {
namespace {

// A master re-exported (6 significant digits, renumbered, turned, scaled and moved) is still the
// original's surface; one with a single vertex dragged off by a tenth of the diagonal is not, nor
// is another shape.
TEST(SameSurface, AnOriginalReExportedIsItsSurfaceAndAnEditedOneIsNot) {
  const Mesh& original = test::procedural_mesh("creature");
  const RegistrationTarget target(original);
  const Mesh exported = round_digits(reorder(transform_mesh(original, random_similarity(original, 11)), 12), 6);
  const SurfaceMatch same = match_surface(exported, target);
  EXPECT_TRUE(same.same);
  EXPECT_LT(same.mrms_relative, 1e-6);

  Mesh dragged = original;
  dragged.V.row(0) += 0.1 * target.diagonal * Eigen::RowVector3d(1, 0, 0);
  EXPECT_FALSE(match_surface(dragged, target).same);
  EXPECT_FALSE(match_surface(test::procedural_mesh("creature_small"), target).same);
}

}  // namespace
}  // namespace meshmark
