#include "core/param/progressive_sphere_map.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>
#include <set>

#include "core/mesh/orientation.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "core/mesh/spherical_area.hpp"
#include "core/param/check_spherical_map.hpp"
#include "core/param/progressive_mesh.hpp"
#include "core/param/sphere_param.hpp"
#include "core/param/spherical_stretch.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// The faces of the mesh once the first `active` vertices of the insertion order are in.
Faces level_faces(const ProgressiveMesh& pm, const Faces& F, Eigen::Index n, Eigen::Index active) {
  const std::vector<int> order = insertion_order(pm);
  std::vector<int> parent(static_cast<std::size_t>(n), -1), rep(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < pm.collapses(); ++i) parent[static_cast<std::size_t>(pm.removed[i])] = pm.kept[i];
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto v = static_cast<std::size_t>(order[static_cast<std::size_t>(j)]);
    rep[v] = j < active ? static_cast<int>(v) : rep[static_cast<std::size_t>(parent[v])];
  }
  std::vector<int> kept;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = rep[F(f, 0)], b = rep[F(f, 1)], c = rep[F(f, 2)];
    if (a != b && b != c && a != c) kept.insert(kept.end(), {a, b, c});
  }
  return Eigen::Map<const Faces>(kept.data(), static_cast<Eigen::Index>(kept.size() / 3), 3);
}

TEST(ProgressiveMesh, CoarseningEndsInATetrahedronAndEveryLevelIsAClosedGenusZeroManifold) {
  const Mesh& creature = test::procedural_mesh("creature");
  const Faces F = orient_outward(creature.V, creature.F);
  const ProgressiveMesh pm = coarsen_to_tetrahedron(creature.V, F);
  EXPECT_EQ(pm.collapses(), static_cast<std::size_t>(creature.V.rows() - 4));
  EXPECT_EQ(pm.base_faces.rows(), 4);
  for (const Eigen::Index active : {Eigen::Index(4), Eigen::Index(5), Eigen::Index(9), Eigen::Index(100),
                                    Eigen::Index(1000), creature.V.rows() - 1, creature.V.rows()}) {
    const MeshReport r = validate_mesh(Mesh{creature.V, level_faces(pm, F, creature.V.rows(), active)});
    EXPECT_EQ(r.boundary_edges, 0u) << active;
    EXPECT_EQ(r.nonmanifold_edges, 0u) << active;
    EXPECT_EQ(r.nonmanifold_vertices, 0u) << active;
    EXPECT_EQ(r.components, 1u) << active;
    EXPECT_EQ(r.genus.value_or(-1), 0) << active;
    EXPECT_EQ(r.orientation, Orientation::outward) << active;
    EXPECT_EQ(r.vertices - r.isolated_vertices, static_cast<std::size_t>(active));
  }
}

TEST(ProgressiveMesh, EachRingStartsAtTheKeptVertexAndWindsLikeTheFaces) {
  const Mesh& creature = test::procedural_mesh("creature");
  const Faces F = orient_outward(creature.V, creature.F);
  const ProgressiveMesh pm = coarsen_to_tetrahedron(creature.V, F);
  // The first collapse: its ring's triangles (removed, ring[j], ring[j+1]) are faces of the input.
  std::set<std::array<int, 3>> faces;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) faces.insert({F(f, k), F(f, (k + 1) % 3), F(f, (k + 2) % 3)});
  const int v = pm.removed[0], begin = pm.ring_offsets[0], end = pm.ring_offsets[1];
  EXPECT_EQ(pm.ring[static_cast<std::size_t>(begin)], pm.kept[0]);
  for (int j = begin; j < end; ++j) {
    const int a = pm.ring[static_cast<std::size_t>(j)],
              b = pm.ring[static_cast<std::size_t>(j + 1 < end ? j + 1 : begin)];
    EXPECT_TRUE(faces.count({v, a, b})) << v << " " << a << " " << b;
  }
}

// Every level of the refinement is a fold-free map of the mesh so far, proven exactly.
void expect_every_level_fold_free(const Mesh& mesh) {
  const Faces F = orient_outward(mesh.V, mesh.F);
  ProgressiveSphereMapOptions options;
  int levels = 0;
  options.on_level = [&](const Vertices& S, const Faces& faces) {
    const SphericalMapCheck check = check_spherical_map(S, faces);
    EXPECT_EQ(check.flipped_faces, 0u) << "level of " << faces.rows() << " faces";
    EXPECT_NEAR(check.degree, 1.0, 1e-9) << "level of " << faces.rows() << " faces";
    ++levels;
  };
  progressive_sphere_map(mesh.V, F, options);
  EXPECT_GT(levels, 8);
}

TEST(ProgressiveSphereMap, EveryLevelOfALimbedCreatureIsFoldFree) {
  expect_every_level_fold_free(test::procedural_mesh("creature"));
}

TEST(ProgressiveSphereMap, EveryLevelOfAManWithSpreadFingersIsFoldFree) {
  MESHMARK_NEEDS_SHARED();
  expect_every_level_fold_free(test::load_shared("corpus/human_man.obj"));
}

// The splits of a level go in waves, each wave's on several threads, and each colour's descent
// steps in slices the threads take as they come free (10,242 vertices: colours of over a
// thousand, so two or more threads): the map is the one a single thread makes, bit for bit.
TEST(ProgressiveSphereMap, TheMapIsTheSameOnAnyNumberOfThreads) {
  const Mesh mesh = test::procedural_mesh("creature_large");
  const Faces F = orient_outward(mesh.V, mesh.F);
  JobControl one, four;
  one.threads = 1;
  four.threads = 4;
  const ProgressiveSphereMap alone = progressive_sphere_map(mesh.V, F, {}, &one);
  const ProgressiveSphereMap shared = progressive_sphere_map(mesh.V, F, {}, &four);
  EXPECT_TRUE(alone.S == shared.S);
  EXPECT_EQ(alone.kernel_fallbacks, shared.kernel_fallbacks);
  EXPECT_GT(alone.kernel_fallbacks, 0u);
}

TEST(ProgressiveSphereMap, ARegularTetrahedronMapsOntoTheRegularOne) {
  Mesh tetra;
  tetra.V.resize(4, 3);
  tetra.V << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  tetra.F.resize(4, 3);
  tetra.F << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  const SphereParam p = sphere_param(tetra);
  EXPECT_EQ(p.flipped_faces, 0u);
  EXPECT_NEAR(p.degree, 1.0, 1e-12);
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) EXPECT_NEAR(p.S.row(i).dot(p.S.row(j)), -1.0 / 3.0, 1e-9);
}

TEST(ProgressiveSphereMap, ATetrahedronsLargestFaceGetsTheLargestShareOfTheSphere) {
  Mesh corner;  // the corner of a cube: three right triangles and a larger slanted one (face 3)
  corner.V.resize(4, 3);
  corner.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  corner.F.resize(4, 3);
  corner.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  const SphereParam p = sphere_param(corner);
  ASSERT_EQ(p.flipped_faces, 0u);
  std::vector<double> share(4);
  for (int f = 0; f < 4; ++f)
    share[f] = signed_spherical_area(p.S.row(p.F(f, 0)), p.S.row(p.F(f, 1)), p.S.row(p.F(f, 2)));
  for (int f = 0; f < 3; ++f) EXPECT_GT(share[3], share[f]);
}

TEST(ProgressiveSphereMap, AFlatClosedSurfaceMaps) {
  // A hexagon's two sides, each a fan around its own centre: all points on one plane.
  Mesh flat;
  flat.V.resize(8, 3);
  flat.V.row(0) << 0, 0, 0;
  flat.V.row(1) << 0, 0, 0;
  for (int i = 0; i < 6; ++i) flat.V.row(2 + i) << std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0;
  flat.F.resize(12, 3);
  for (int i = 0; i < 6; ++i) {
    flat.F.row(i) << 0, 2 + i, 2 + (i + 1) % 6;
    flat.F.row(6 + i) << 1, 2 + (i + 1) % 6, 2 + i;
  }
  const SphereParam p = sphere_param(flat);
  EXPECT_EQ(p.flipped_faces, 0u);
  EXPECT_NEAR(p.degree, 1.0, 1e-9);
}

TEST(ProgressiveSphereMap, AMeshWithASliverMaps) {
  Mesh creature = test::procedural_mesh("creature");
  // Pull one face's third corner almost onto its opposite edge: a sliver of 1e-9 of its area.
  const int a = creature.F(100, 0), b = creature.F(100, 1), c = creature.F(100, 2);
  const Eigen::RowVector3d mid = 0.5 * (creature.V.row(a) + creature.V.row(b));
  creature.V.row(c) = mid + 1e-9 * (creature.V.row(c) - mid);
  ASSERT_TRUE(validate_mesh(creature).closed_genus_zero);
  const SphereParam p = sphere_param(creature);
  EXPECT_EQ(p.flipped_faces, 0u);
  EXPECT_NEAR(p.degree, 1.0, 1e-9);
}

TEST(SphereParam, ReportsProgressAtLeastEveryTwoPercent) {
  SphereParamOptions options;
  options.progress_from = 0.05;
  options.progress_to = 0.75;
  std::vector<double> seen = {0.05};
  JobControl control;
  control.report = [&](const std::string& stage, double progress) {
    EXPECT_EQ(stage, "parameterize");
    seen.push_back(progress);
  };
  sphere_param(test::procedural_mesh("creature_large"), options, &control);
  ASSERT_GT(seen.size(), 30u);
  for (std::size_t i = 1; i < seen.size(); ++i) {
    EXPECT_GE(seen[i], seen[i - 1]) << i;
    EXPECT_LE(seen[i] - seen[i - 1], 0.02 * 0.7 + 0.002) << "a jump at report " << i;
  }
  EXPECT_GT(seen.back(), 0.74);
}

TEST(SphericalStretch, TheGradientIsTheEnergysDerivative) {
  const Eigen::Vector3d p0 = Eigen::Vector3d(0.2, 0.1, 1).normalized(), p1 = Eigen::Vector3d(0.5, -0.1, 1).normalized(),
                        p2 = Eigen::Vector3d(0.1, 0.6, 1).normalized();
  const StretchTarget t = face_target({0, 0, 0}, {1, 0, 0}, {0.3, 0.8, 0});
  Eigen::Vector3d g;
  stretch_energy_gradient(p0, p1, p2, t, g);
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d h = Eigen::Vector3d::Zero();
    h[k] = 1e-7;
    const double numeric = (stretch_energy(p0 + h, p1, p2, t) - stretch_energy(p0 - h, p1, p2, t)) / 2e-7;
    EXPECT_NEAR(g[k], numeric, 1e-5 * std::max(1.0, std::abs(numeric))) << k;
  }
}

// The energy takes √D as 2·area, which is exact only if the square root of a rounded square
// rounds back to its root (true of binary floating point above underflow): checked over the
// magnitudes an area can have, so that a platform where it fails is caught here.
TEST(SphericalStretch, TheRootOfFourTimesAnAreaSquaredIsTwiceTheAreaBitForBit) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> exponent(-150, 3), mantissa(1, 10);
  for (int i = 0; i < 1000000; ++i) {
    const double area = mantissa(random) * std::pow(10.0, exponent(random));
    ASSERT_EQ(std::sqrt(4 * area * area), 2 * area) << std::hexfloat << area;
  }
}

TEST(SphericalStretch, TheEnergyIsLeastForTheTargetShapeAndBlowsUpAsTheImageDegenerates) {
  const StretchTarget t = equilateral_target(1.0);
  const double s = 0.05;  // a small equilateral triangle on the sphere, and squashed versions
  const Eigen::Vector3d n(0, 0, 1);
  const auto at = [&](double x, double y) { return Eigen::Vector3d(x, y, 1).normalized(); };
  const double equilateral = stretch_energy(at(0, 0), at(s, 0), at(s / 2, s * std::sqrt(3.0) / 2), t);
  const double squashed = stretch_energy(at(0, 0), at(s, 0), at(s / 2, s * 0.1), t);
  const double flat = stretch_energy(at(0, 0), at(s, 0), at(s / 2, s * 1e-9), t);
  EXPECT_LT(equilateral, squashed);
  EXPECT_GT(flat, 1e6 * equilateral);
  (void)n;
}

// The genus-0 meshes nobody here made: every one maps, proven bijective, with every face's
// share of the sphere at least 5 % of its share of the surface for 95 % of the faces.
class CorpusSphere : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { MESHMARK_NEEDS_SHARED_FOR(GetParam()); }
};

TEST_P(CorpusSphere, MapsBijectivelyWithAFairShareOfAreaForNearlyEveryFace) {
  const SphereParam p = sphere_param(test::named_mesh(GetParam()));
  EXPECT_EQ(p.flipped_faces, 0u);
  EXPECT_NEAR(p.degree, 1.0, 1e-9);
  EXPECT_TRUE(check_spherical_map(p.S, p.F).bijective());
  EXPECT_GE(p.area_distortion.p05, 0.05);
}

INSTANTIATE_TEST_SUITE_P(GenusZero, CorpusSphere,
                         ::testing::Values("procedural/creature", "procedural/creature_large", "bunny.obj",
                                           "mannequin.off", "spot.obj", "armadillo.obj", "corpus/human_man.obj",
                                           "corpus/scorpion_lowres.obj", "corpus/sword.obj", "corpus/arm.obj",
                                           "corpus/cheburashka.obj", "corpus/fandisk.obj", "corpus/homer.obj",
                                           "corpus/cat.obj", "corpus/fish.obj", "corpus/goathead.obj",
                                           "corpus/plane.obj", "corpus/screwdriver.off", "corpus/elephant.obj",
                                           "corpus/hand_closed.obj"),
                         [](const auto& info) {
                           std::string name = info.param;
                           name = name.substr(name.rfind('/') + 1);
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace meshmark
