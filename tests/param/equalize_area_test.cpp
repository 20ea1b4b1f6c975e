#include "core/param/equalize_area.hpp"

#include <gtest/gtest.h>

#include "core/param/check_spherical_map.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/param/sphere_param.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// The conformal map of a creature with evenly spaced vertices (its limbs shrunk), once per
// test binary.
const SphereParam& conformal_creature() {
  static const SphereParam p = [] {
    SphereParamOptions options;
    options.method = SphereMethod::conformal_flow;
    options.equalize_area = false;
    return sphere_param(test::procedural_mesh("creature_scan"), options);
  }();
  return p;
}

TEST(EqualizeArea, KeepsTheMapBijective) {
  const Mesh& creature = test::procedural_mesh("creature_scan");
  Vertices S = conformal_creature().S;
  equalize_area(S, conformal_creature().F, face_areas(creature.V, conformal_creature().F));
  const SphericalMapCheck check = check_spherical_map(S, conformal_creature().F);
  EXPECT_EQ(check.flipped_faces, 0u);
  EXPECT_NEAR(check.degree, 1.0, 1e-9);
}

TEST(EqualizeArea, NarrowsTheSpreadOfAreaRatios) {
  const Mesh& creature = test::procedural_mesh("creature_scan");
  Vertices S = conformal_creature().S;
  const EqualizeAreaResult r = equalize_area(S, conformal_creature().F, face_areas(creature.V, conformal_creature().F));
  const AreaDistortion before = area_distortion(creature.V, conformal_creature().S, conformal_creature().F);
  const AreaDistortion after = area_distortion(creature.V, S, conformal_creature().F);
  EXPECT_GT(after.p05, 10 * before.p05);  // the shrunk tips got a fair share back
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
  const SphereParam p = sphere_param(test::procedural_mesh("creature_scan"), options);
  EXPECT_GT(p.equalization.steps, 0);
  EXPECT_GT(p.area_distortion.p05, p.map_area_distortion.p05);
  EXPECT_EQ(p.flipped_faces, 0u);
}

}  // namespace
}  // namespace meshmark
