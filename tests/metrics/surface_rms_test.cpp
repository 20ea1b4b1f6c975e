#include "core/metrics/surface_rms.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace meshmark {
namespace {

Mesh unit_square() {
  Mesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  return m;
}

TEST(SurfaceRms, OfAConstantIsThatConstant) {
  EXPECT_NEAR(surface_rms(unit_square(), Eigen::VectorXd::Constant(4, -0.3)), 0.3, 1e-15);
}

// u = x on the unit square: ∫ x² over [0,1]² is 1/3, exactly, for a linear field.
TEST(SurfaceRms, IntegratesALinearFieldExactly) {
  const Mesh m = unit_square();
  EXPECT_NEAR(surface_rms(m, m.V.col(0)), std::sqrt(1.0 / 3.0), 1e-15);
}

// One vertex up, its neighbours down: the surface sees less than the vertex values say.
TEST(SurfaceRms, IsBelowTheVertexRmsForAnAlternatingField) {
  Eigen::VectorXd u(4);
  u << 1, -1, 1, -1;
  EXPECT_LT(surface_rms(unit_square(), u), 0.6);
}

TEST(SurfaceRms, RefusesAFieldOfTheWrongSize) {
  EXPECT_THROW(surface_rms(unit_square(), Eigen::VectorXd::Zero(3)), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark
