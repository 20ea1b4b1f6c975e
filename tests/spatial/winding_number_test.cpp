// The generalized winding number: 1 inside a closed surface wound outward and 0 outside (−1
// wound inward), a jump of one across an open surface, and the clustered sum within three
// hundredths of the plain sum over every triangle (what deciding a side needs).

#include "core/spatial/winding_number.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/procedural_meshes.hpp"

namespace meshmark {
namespace {

// Every triangle's solid angle summed, by l'Huilier's theorem (a formula of its own).
double brute_force_winding(const Mesh& mesh, const Eigen::Vector3d& p) {
  double total = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    Eigen::Vector3d corner[3];
    for (int k = 0; k < 3; ++k) corner[k] = (mesh.V.row(mesh.F(f, k)).transpose() - p).normalized();
    const double a = std::acos(std::clamp(corner[1].dot(corner[2]), -1.0, 1.0)),
                 b = std::acos(std::clamp(corner[2].dot(corner[0]), -1.0, 1.0)),
                 c = std::acos(std::clamp(corner[0].dot(corner[1]), -1.0, 1.0)), s = (a + b + c) / 2;
    const double excess = 4 * std::atan(std::sqrt(std::max(0.0, std::tan(s / 2) * std::tan((s - a) / 2) *
                                                                    std::tan((s - b) / 2) * std::tan((s - c) / 2))));
    total += corner[0].dot(corner[1].cross(corner[2])) >= 0 ? excess : -excess;
  }
  return total / (4 * M_PI);
}

Mesh flipped(Mesh mesh) {
  mesh.F.col(1).swap(mesh.F.col(2));
  return mesh;
}

// The unit sphere without its faces above z = 0.6: a cap-shaped hole.
Mesh sphere_with_hole() {
  const Mesh sphere = icosphere(3);
  Mesh open{sphere.V, Faces(0, 3)};
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
    const double z = (sphere.V(sphere.F(f, 0), 2) + sphere.V(sphere.F(f, 1), 2) + sphere.V(sphere.F(f, 2), 2)) / 3;
    if (z > 0.6) continue;
    open.F.conservativeResize(open.F.rows() + 1, 3);
    open.F.row(open.F.rows() - 1) = sphere.F.row(f);
  }
  return open;
}

TEST(WindingNumber, IsOneInsideAClosedSurfaceAndZeroOutsideAndMinusOneWoundInward) {
  const Mesh sphere = icosphere(3);
  const WindingNumber outward(sphere.V, sphere.F);
  const Mesh inward_mesh = flipped(sphere);
  const WindingNumber inward(inward_mesh.V, inward_mesh.F);
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.9, 0, 0), Eigen::Vector3d(0.3, -0.5, 0.6)}) {
    EXPECT_NEAR(outward.at(p), 1, 0.03);
    EXPECT_NEAR(inward.at(p), -1, 0.03);
  }
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(1.1, 0, 0), Eigen::Vector3d(3, 2, 1), Eigen::Vector3d(-40, 0, 9)})
    EXPECT_NEAR(outward.at(p), 0, 0.03);
}

TEST(WindingNumber, JumpsByOneAcrossAnOpenSurfaceAndItsHalfClosesTheHole) {
  const Mesh open = sphere_with_hole();
  const WindingNumber winding(open.V, open.F);
  for (const Eigen::Vector3d& direction :
       {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, -1, -1), Eigen::Vector3d(0.5, 0.2, 0.3)}) {
    const Eigen::Vector3d on = direction.normalized();
    EXPECT_NEAR(winding.at(0.97 * on) - winding.at(1.03 * on), 1, 0.1);
    EXPECT_GT(winding.at(0.97 * on), 0.5);
    EXPECT_LT(winding.at(1.03 * on), 0.5);
  }
  EXPECT_GT(winding.at(Eigen::Vector3d(0, 0, 0.3)), 0.5);  // below the hole: inside
  EXPECT_LT(winding.at(Eigen::Vector3d(0, 0, 1.2)), 0.5);  // above it: outside
}

TEST(WindingNumber, TheClusteredSumIsThePlainSumWithinThreeHundredths) {
  const Mesh open = sphere_with_hole();
  const WindingNumber winding(open.V, open.F);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-1.6, 1.6);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    ASSERT_NEAR(winding.at(p), brute_force_winding(open, p), 0.03) << p.transpose();
  }
}

}  // namespace
}  // namespace meshmark
