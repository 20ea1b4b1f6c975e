// Reading by projection on an exact case: a sphere read against a larger concentric sphere.

#include "core/watermark/measure_by_projection.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

Vertices face_normals_of(const Mesh& m) {
  Vertices N(m.F.rows(), 3);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    N.row(f) = (b - a).cross(c - a).normalized().transpose();
  }
  return N;
}

TEST(MeasureByProjection, AConcentricOffsetSphereReadsAsItsOffsetEverywhere) {
  const Mesh original = test::icosphere(3);
  Mesh suspect = test::icosphere(4);  // another tessellation: every suspect point is new
  const double offset = 0.004;        // about the sagitta of the original's faces
  suspect.V *= 1.0 + offset;
  const AabbTree tree(original.V, original.F);
  const Displacement d = measure_by_projection(tree, original, face_normals_of(original), suspect, 2.0);
  EXPECT_EQ(d.missing, 0u);
  // The original's flat faces sit inside the sphere by up to their sagitta (≈ 0.004 here): the
  // read offset is the true one plus a share of that gap, outward everywhere, and close to it.
  EXPECT_GT(d.t.minCoeff(), 0.0);
  EXPECT_NEAR(d.t.mean(), offset, 0.004);
}

TEST(MeasureByProjection, ASuspectAwayFromPartOfTheOriginalLeavesThoseVerticesMissing) {
  const Mesh original = test::icosphere(3);
  Mesh suspect = test::icosphere(4);
  // Keep only the suspect's faces with z > 0: the southern vertices get no samples.
  std::vector<Eigen::Index> kept;
  for (Eigen::Index f = 0; f < suspect.F.rows(); ++f)
    if (suspect.V(suspect.F(f, 0), 2) > 0.1 && suspect.V(suspect.F(f, 1), 2) > 0.1 &&
        suspect.V(suspect.F(f, 2), 2) > 0.1)
      kept.push_back(f);
  Faces F(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) F.row(static_cast<Eigen::Index>(i)) = suspect.F.row(kept[i]);
  suspect.F = F;
  const AabbTree tree(original.V, original.F);
  const Displacement d = measure_by_projection(tree, original, face_normals_of(original), suspect, 2.0);
  std::size_t south_found = 0;
  for (Eigen::Index v = 0; v < original.V.rows(); ++v)
    if (original.V(v, 2) < -0.2) south_found += d.found[static_cast<std::size_t>(v)];
  EXPECT_EQ(south_found, 0u);
  EXPECT_GT(d.missing, static_cast<std::size_t>(original.V.rows() / 4));
}

// The samples are queried in Z-order of the suspect's faces, in blocks split among the threads,
// and summed in that order: the reading is the same bit for bit on any thread count.
TEST(MeasureByProjection, TheReadingIsTheSameOnAnyThreadCount) {
  const Mesh original = test::icosphere(6);  // 40,962 vertices: 245,772 samples, four blocks
  Mesh suspect = test::icosphere(5);
  for (Eigen::Index v = 0; v < suspect.V.rows(); ++v) suspect.V.row(v) *= 1.0 + 0.003 * std::sin(7.0 * v);
  const AabbTree tree(original.V, original.F);
  const Vertices normals = face_normals_of(original);
  const Displacement one = measure_by_projection(tree, original, normals, suspect, 2.0, {}, 1);
  for (const int threads : {2, 3, 8}) {
    const Displacement d = measure_by_projection(tree, original, normals, suspect, 2.0, {}, threads);
    EXPECT_TRUE(d.t == one.t) << threads;
    EXPECT_EQ(d.found, one.found);
  }
  EXPECT_EQ(one.missing, 0u);
}

}  // namespace
}  // namespace meshmark
