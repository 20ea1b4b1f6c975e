#include "core/basis/multiscale_bumps.hpp"

#include <gtest/gtest.h>

#include <set>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// creature and a cube beside it: one component that carries, one too small to.
Mesh creature_and_a_cube() { return test::side_by_side(test::procedural_mesh("creature"), test::cube()); }

TEST(MultiscaleBumps, BandsGrowFourfoldAndNarrowDownToTheSupportLimit) {
  const Mesh& creature = test::procedural_mesh("creature");
  const BumpBasis b = multiscale_bumps(creature);
  ASSERT_GE(b.bands(), 2);
  std::vector<int> per_band(static_cast<std::size_t>(b.bands()), 0);
  for (int band : b.band) ++per_band[static_cast<std::size_t>(band)];
  for (int k = 1; k < b.bands(); ++k) {
    EXPECT_NEAR(static_cast<double>(per_band[k]) / per_band[k - 1], 4.0, 1.0) << "band " << k;
    EXPECT_LT(b.band_support[k], b.band_support[k - 1]);
  }
  // The finest band covers about what it was sized for (graph distance reaches a little less).
  EXPECT_NEAR(b.band_support.back(), BumpBasisOptions{}.finest_support_vertices,
              0.35 * BumpBasisOptions{}.finest_support_vertices);
}

TEST(MultiscaleBumps, EveryBumpPeaksAtOneAtItsCentreAndStaysWithinZeroAndOne) {
  const BumpBasis b = multiscale_bumps(test::procedural_mesh("creature"));
  for (Eigen::Index k = 0; k < b.values.cols(); ++k) {
    EXPECT_DOUBLE_EQ(b.values.coeff(b.center[static_cast<std::size_t>(k)], k), 1.0);
    for (Eigen::SparseMatrix<double>::InnerIterator it(b.values, k); it; ++it) {
      EXPECT_GT(it.value(), 0.0);
      EXPECT_LE(it.value(), 1.0);
    }
  }
}

TEST(MultiscaleBumps, NoBumpCrossesComponentsAndTinyComponentsGetNone) {
  const Mesh both = creature_and_a_cube();
  const BumpBasis b = multiscale_bumps(both);
  EXPECT_EQ(b.marked_components, 1u);
  EXPECT_EQ(b.skipped_components, 1u);
  EXPECT_EQ(b.skipped_vertices, 8u);
  const Eigen::Index spot_vertices = both.V.rows() - 8;
  for (Eigen::Index k = 0; k < b.values.cols(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(b.values, k); it; ++it) EXPECT_LT(it.row(), spot_vertices);
  for (Eigen::Index v = spot_vertices; v < both.V.rows(); ++v) EXPECT_EQ(b.component[static_cast<std::size_t>(v)], -1);
}

TEST(MultiscaleBumps, TheBasisDependsOnlyOnTheMesh) {
  const Mesh& torus = test::procedural_mesh("torus");
  const BumpBasis a = multiscale_bumps(torus), b = multiscale_bumps(torus);
  EXPECT_EQ(a.center, b.center);
  EXPECT_TRUE(Eigen::MatrixXd(a.values - b.values).isZero(0.0));
}

}  // namespace
}  // namespace meshmark
