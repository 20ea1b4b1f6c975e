// The stretch energy of one face, on one lane (double) and on two at once (Eigen::Array2d): the
// descent evaluates a star's faces in pairs, and must get the bits of each face alone, since any
// change to the map's arithmetic is a change of method for copies read with --original alone.
#include "core/param/stretch_face.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>

#include "core/param/spherical_stretch.hpp"

namespace meshmark {
namespace {

using stretch_face::Pair;
using Point1 = stretch_face::Point<double>;
using Point2 = stretch_face::Point<Pair>;

std::uint64_t bits(double value) { return std::bit_cast<std::uint64_t>(value); }

struct Face {
  Point1 p0, a, b;
  stretch_face::Target<double> target;
};

Point1 point_of(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// Faces on the unit sphere from 1e-6 of its radius to across it, some degenerate (a corner on
// the great circle through the other two), some turned over; targets equilateral or skewed.
Face random_face(std::mt19937_64& random) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  const auto direction = [&] { return Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized(); };
  const Eigen::Vector3d centre = direction();
  const double size = std::pow(10.0, -6 * uniform(random));
  const auto near = [&] { return Eigen::Vector3d((centre + size * direction()).normalized()); };
  Eigen::Vector3d p0 = near(), p1 = near(), p2 = near();
  const double kind = uniform(random);
  if (kind < 0.1) p2 = (p0 + p1).normalized();
  else if (kind < 0.2) std::swap(p1, p2);
  else if (kind < 0.25) p1 = direction(), p2 = direction();
  const StretchTarget t = uniform(random) < 0.3 ? equilateral_target(uniform(random))
                                                : face_target(direction(), direction(), 2 * direction());
  return {point_of(p0), point_of(p1), point_of(p2), {t.mass, t.l[0], t.l[1], t.l[2]}};
}

Pair lanes(double first, double second) { return {first, second}; }
Point2 lanes(const Point1& p, const Point1& q) { return {lanes(p.x, q.x), lanes(p.y, q.y), lanes(p.z, q.z)}; }
stretch_face::Target<Pair> lanes(const stretch_face::Target<double>& s, const stretch_face::Target<double>& t) {
  return {lanes(s.mass, t.mass), lanes(s.l0, t.l0), lanes(s.l1, t.l1), lanes(s.l2, t.l2)};
}

TEST(StretchFace, TwoFacesInThePairsLanesGiveTheBitsOfEachFaceAlone) {
  std::mt19937_64 random(11);
  for (int trial = 0; trial < 200000; ++trial) {
    const Face one = random_face(random), two = random_face(random);
    // Both lanes evaluate at one vertex position, as a star's faces do.
    const Point2 at = lanes(one.p0, one.p0);
    const auto edge = stretch_face::far_edge(lanes(one.a, two.a), lanes(one.b, two.b));
    const auto target = lanes(one.target, two.target);
    const auto m = stretch_face::measure(at, edge, target);
    Point2 gradient{};
    const Pair energy = stretch_face::energy_gradient_at(m, at, edge, target, gradient);
    const Pair energy_only = stretch_face::energy_at(m, target.mass);
    const Pair sign_bound = stretch_face::volume_sign_bound(at, edge);
    for (int lane = 0; lane < 2; ++lane) {
      const Face& face = lane == 0 ? one : two;
      const auto e = stretch_face::far_edge(face.a, face.b);
      const auto m1 = stretch_face::measure(one.p0, e, face.target);
      Point1 g{};
      const double E = stretch_face::energy_gradient_at(m1, one.p0, e, face.target, g);
      SCOPED_TRACE(testing::Message() << "trial " << trial << ", lane " << lane);
      ASSERT_EQ(bits(m.volume[lane]), bits(m1.volume));
      ASSERT_EQ(bits(m.area[lane]), bits(m1.area));
      ASSERT_EQ(bits(m.N[lane]), bits(m1.N));
      ASSERT_EQ(bits(energy[lane]), bits(E));
      ASSERT_EQ(bits(energy_only[lane]), bits(stretch_face::energy_at(m1, face.target.mass)));
      ASSERT_EQ(bits(gradient.x[lane]), bits(g.x));
      ASSERT_EQ(bits(gradient.y[lane]), bits(g.y));
      ASSERT_EQ(bits(gradient.z[lane]), bits(g.z));
      ASSERT_EQ(bits(sign_bound[lane]), bits(stretch_face::volume_sign_bound(one.p0, e)));
    }
  }
}

// The energy's arithmetic, pinned to the bits the maps of every copy marked so far were made
// with (computed by the per-face code of 1060b43, before the pairs).
TEST(StretchFace, TheEnergyOfAFaceKeepsTheBitsOfTheMapsAlreadyMade) {
  const Eigen::Vector3d p0 = Eigen::Vector3d(0.3, 0.4, 0.866).normalized();
  const Eigen::Vector3d p1 = Eigen::Vector3d(0.35, 0.38, 0.86).normalized();
  const Eigen::Vector3d p2 = Eigen::Vector3d(0.31, 0.45, 0.84).normalized();
  const StretchTarget t = face_target({0, 0, 0}, {1, 0.1, 0}, {0.2, 0.9, 0.3});
  Eigen::Vector3d g;
  EXPECT_EQ(stretch_energy_gradient(p0, p1, p2, t, g), 0x1.203f0d5547c2bp+6);
  EXPECT_EQ(g.x(), 0x1.bbca00b8f9f27p+10);
  EXPECT_EQ(g.y(), 0x1.5bd30549ffd7p+9);
  EXPECT_EQ(g.z(), -0x1.e70d45e8362bfp+9);
  EXPECT_EQ(stretch_energy(p0, p1, p2, t), 0x1.203f0d5547c2bp+6);
}

}  // namespace
}  // namespace meshmark
