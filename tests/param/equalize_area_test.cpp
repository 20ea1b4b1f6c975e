#include "core/param/equalize_area.hpp"

#include <gtest/gtest.h>

#include "core/param/check_spherical_map.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/param/sphere_param.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// The conformal map of spot (its horns and ears shrunk), once per test binary.
const SphereParam& conformal_spot() {
  static const SphereParam p = [] {
    SphereParamOptions options;
    options.method = SphereMethod::conformal_flow;
    options.equalize_area = false;
    return sphere_param(test::load_shared("spot.obj"), options);
  }();
  return p;
}

TEST(EqualizeArea, KeepsTheMapBijective) {
  const Mesh& spot = test::load_shared("spot.obj");
  Vertices S = conformal_spot().S;
  equalize_area(S, conformal_spot().F, face_areas(spot.V, conformal_spot().F));
  const SphericalMapCheck check = check_spherical_map(S, conformal_spot().F);
  EXPECT_EQ(check.flipped_faces, 0u);
  EXPECT_NEAR(check.degree, 1.0, 1e-9);
}

TEST(EqualizeArea, NarrowsTheSpreadOfAreaRatios) {
  const Mesh& spot = test::load_shared("spot.obj");
  Vertices S = conformal_spot().S;
  const EqualizeAreaResult r = equalize_area(S, conformal_spot().F, face_areas(spot.V, conformal_spot().F));
  const AreaDistortion before = area_distortion(spot.V, conformal_spot().S, conformal_spot().F);
  const AreaDistortion after = area_distortion(spot.V, S, conformal_spot().F);
  EXPECT_GT(after.p05, 10 * before.p05);     // the shrunk tips got a fair share back
  EXPECT_LT(after.p95 / after.p05, before.p95 / before.p05 / 10);
  EXPECT_LT(r.spread_after, r.spread_before);
}

TEST(EqualizeArea, LeavesAnAlreadyEqualAreaMapAlmostUnchanged) {
  const Mesh sphere = test::icosphere(4);  // its own spherical image: nearly equal areas already
  Vertices S = sphere.V;
  equalize_area(S, sphere.F, face_areas(sphere.V, sphere.F));
  EXPECT_LT((S - sphere.V).rowwise().norm().maxCoeff(), 0.05);
  EXPECT_TRUE(check_spherical_map(S, sphere.F).bijective());
}

TEST(SphereParam, AreaCorrectionFollowsTheConformalFlowAndStaysBijective) {
  SphereParamOptions options;
  options.method = SphereMethod::conformal_flow;
  const SphereParam p = sphere_param(test::load_shared("spot.obj"), options);
  EXPECT_GT(p.equalization.steps, 0);
  EXPECT_GT(p.area_distortion.p05, p.map_area_distortion.p05);
  EXPECT_EQ(p.flipped_faces, 0u);
}

}  // namespace
}  // namespace meshmark
