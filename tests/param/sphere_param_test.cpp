#include "core/param/sphere_param.hpp"

#include <gtest/gtest.h>

#include "core/param/check_spherical_map.hpp"
#include "core/param/mobius_center.hpp"
#include "core/param/repair_spherical_flips.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(CheckSphericalMap, IcosphereIsBijectiveOfDegreeOne) {
  const Mesh sphere = test::icosphere(3);
  const SphericalMapCheck check = check_spherical_map(sphere.V, sphere.F);
  EXPECT_EQ(check.flipped_faces, 0u);
  EXPECT_NEAR(check.degree, 1.0, 1e-12);
  EXPECT_TRUE(check.bijective());
}

TEST(CheckSphericalMap, ReversedFacesHaveDegreeMinusOne) {
  Mesh sphere = test::icosphere(2);
  sphere.F.col(1).swap(sphere.F.col(2));
  const SphericalMapCheck check = check_spherical_map(sphere.V, sphere.F);
  EXPECT_EQ(check.flipped_faces, static_cast<std::size_t>(sphere.F.rows()));
  EXPECT_NEAR(check.degree, -1.0, 1e-12);
}

TEST(CheckSphericalMap, AVertexPushedPastItsNeighboursFlipsFaces) {
  Mesh sphere = test::icosphere(2);
  sphere.V.row(0) = -sphere.V.row(0);  // a vertex moved to the far side
  const SphericalMapCheck check = check_spherical_map(sphere.V, sphere.F);
  EXPECT_GT(check.flipped_faces, 0u);
  EXPECT_FALSE(check.bijective());
}

TEST(RepairSphericalFlips, RestoresABijectionAfterALocalFold) {
  Mesh sphere = test::icosphere(3);
  // Drag one vertex across two of its neighbours: a local fold.
  const int v = sphere.F(0, 0), u = sphere.F(0, 1);
  sphere.V.row(v) = (sphere.V.row(u) * 2.0 - sphere.V.row(v)).normalized();
  ASSERT_GT(check_spherical_map(sphere.V, sphere.F).flipped_faces, 0u);
  const RepairResult repair = repair_spherical_flips(sphere.V, sphere.F);
  EXPECT_TRUE(repair.success);
  EXPECT_TRUE(check_spherical_map(sphere.V, sphere.F).bijective());
}

TEST(MobiusCenter, MovesTheWeightedCentreOfMassToTheOrigin) {
  Mesh sphere = test::icosphere(3);
  for (Eigen::Index i = 0; i < sphere.V.rows(); ++i)
    sphere.V.row(i) = mobius_transform(sphere.V.row(i).transpose(), {0.4, -0.2, 0.1});
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(sphere.V.rows());
  ASSERT_GT(sphere.V.colwise().mean().norm(), 0.1);
  const MobiusCenterResult r = mobius_center(sphere.V, w);
  EXPECT_LT(r.residual, 1e-9);
  EXPECT_LT(sphere.V.colwise().mean().norm(), 1e-9);
  EXPECT_TRUE(check_spherical_map(sphere.V, sphere.F).bijective());  // Möbius maps keep orientation
}

TEST(MobiusTransform, MapsTheSphereToItself) {
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.6, 0.8, 0), Eigen::Vector3d(0, 0, -1)})
    EXPECT_NEAR(mobius_transform(x, {0.3, 0.5, -0.2}).norm(), 1.0, 1e-14);
}

class SharedMeshParam : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { MESHMARK_NEEDS_SHARED_FOR(GetParam()); }
};

TEST_P(SharedMeshParam, IsBijectiveWithDegreeOne) {
  const Mesh& mesh = test::named_mesh(GetParam());
  const SphereParam p = sphere_param(mesh);
  EXPECT_EQ(p.flipped_faces, 0u);
  EXPECT_NEAR(p.degree, 1.0, 1e-9);
  EXPECT_NEAR(p.S.rowwise().norm().maxCoeff(), 1.0, 1e-12);
  EXPECT_TRUE(check_spherical_map(p.S, p.F).bijective());  // re-proven independently
}

INSTANTIATE_TEST_SUITE_P(ValidMeshes, SharedMeshParam,
                         ::testing::Values("bunny.obj", "mannequin.off", "spot.obj", "armadillo.obj",
                                           "procedural/creature", "procedural/creature_large"));

TEST(SphereParam, IsDeterministicBitForBit) {
  const Mesh& mesh = test::procedural_mesh("creature");
  const SphereParam a = sphere_param(mesh), b = sphere_param(mesh);
  EXPECT_TRUE(a.S == b.S);
}

TEST(SphereParam, InwardMeshIsFlippedAndMapped) {
  Mesh mesh = test::procedural_mesh("creature");
  mesh.F.col(1).swap(mesh.F.col(2));
  const SphereParam p = sphere_param(mesh);
  EXPECT_TRUE(p.flipped_input);
  EXPECT_EQ(p.flipped_faces, 0u);
  EXPECT_NEAR(p.degree, 1.0, 1e-9);
}

TEST(SphereParam, CoarseCubeIsMapped) {
  const SphereParam p = sphere_param(test::cube());
  EXPECT_EQ(p.flipped_faces, 0u);
  EXPECT_NEAR(p.degree, 1.0, 1e-9);
}

}  // namespace
}  // namespace meshmark

namespace meshmark {
namespace {

TEST(SphereParam, ACancelStopsTheParameterizationInsideItsStages) {
  std::atomic<bool> cancel{true};
  JobControl control;
  control.cancel = &cancel;
  EXPECT_THROW(sphere_param(test::procedural_mesh("creature"), {}, &control), Canceled);
}

}  // namespace
}  // namespace meshmark
