#include "core/metrics/compare_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/mesh/massmatrix.hpp"
#include "core/mesh/vertex_normals.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(CompareMeshes, AMeshAgainstItselfIsZero) {
  const Mesh& m = test::procedural_mesh("creature_large");
  const SurfaceDistance d = compare_meshes(m, m, {50000});
  EXPECT_LT(d.mrms_relative(), 1e-12);
  EXPECT_LT(d.hausdorff_relative(), 1e-12);
}

TEST(CompareMeshes, AnOffsetSphereIsAboutTheOffsetAway) {
  // A fine icosphere of radius 1 against one moved out along its normals by d: distance d.
  const Mesh sphere = test::icosphere(5);
  const double d = 0.01;
  Mesh outer = sphere;
  outer.V += d * vertex_normals(sphere.V, sphere.F);
  const SurfaceDistance r = compare_meshes(sphere, outer, {100000});
  EXPECT_NEAR(r.mrms, d, 0.02 * d);
  EXPECT_NEAR(r.hausdorff, d, 0.05 * d);
  EXPECT_DOUBLE_EQ(r.mrms_relative(), r.mrms / r.diagonal);
}

TEST(CompareMeshes, AnOffsetMeshAlongItsNormalsIsAboutTheOffsetAway) {
  const Mesh& m = test::procedural_mesh("creature_large");
  const double diagonal = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm(), d = 1e-4 * diagonal;
  Mesh offset = m;
  offset.V += d * vertex_normals(m.V, m.F);
  const SurfaceDistance r = compare_meshes(m, offset, {100000});
  EXPECT_NEAR(r.mrms, d, 0.1 * d);
}

TEST(CompareMeshes, IsTheLargerOfTheTwoSides) {
  // A piece of a surface: every point of it is on the whole, but not the other way round.
  const Mesh whole = test::icosphere(3);
  Mesh half = whole;
  std::vector<int> keep;
  for (Eigen::Index f = 0; f < whole.F.rows(); ++f)
    if (whole.V(whole.F(f, 0), 2) > 0) keep.push_back(static_cast<int>(f));
  half.F.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t i = 0; i < keep.size(); ++i) half.F.row(static_cast<Eigen::Index>(i)) = whole.F.row(keep[i]);
  const SurfaceDistance r = compare_meshes(whole, half, {20000});
  EXPECT_LT(r.rms_ba, 1e-12);
  EXPECT_GT(r.rms_ab, 0.1);
  EXPECT_EQ(r.mrms, r.rms_ab);
}

// A copy on the original's faces queries only the vertices that moved more than the samples' max
// (the rest are bounded by their own displacement): its Hausdorff distance is the one every vertex
// queried gives, which the same surface with its faces listed in another order still computes.
TEST(CompareMeshes, ACopyOnTheSameFacesHasTheMaxOfEveryVertexQueried) {
  const Mesh& original = test::procedural_mesh("creature");
  Mesh moved = original;
  for (Eigen::Index v = 0; v < moved.V.rows(); ++v) moved.V.row(v) *= 1.0 + 0.002 * std::sin(3.0 * v);
  const auto faces_reversed = [](Mesh m) {
    m.F = m.F.colwise().reverse().eval();
    return m;
  };
  const SurfaceDistance shared = compare_meshes(original, moved, {20000});
  EXPECT_GT(shared.max_ab, 0.0);
  EXPECT_EQ(shared.max_ab, compare_meshes(original, faces_reversed(moved), {20000}).max_ab);
  EXPECT_EQ(compare_meshes(moved, original, {20000}).max_ab,
            compare_meshes(moved, faces_reversed(original), {20000}).max_ab);
}

TEST(SampleSurface, IsUniformByArea) {
  const Mesh cube = test::cube();
  const Vertices P = sample_surface(cube, 60000);
  // Each of the six faces holds a sixth of the samples.
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {0.0, 1.0}) {
      int on = 0;
      for (Eigen::Index i = 0; i < P.rows(); ++i) on += std::abs(P(i, axis) - side) < 1e-12;
      EXPECT_NEAR(on / 60000.0, 1.0 / 6, 0.005);
    }
}

// Stratified by area: the samples come face by face, and each face holds its share of them to
// within one, however unequal the faces.
TEST(SampleSurface, EachFaceHoldsItsShareToWithinOneSample) {
  const Mesh mesh = test::procedural_mesh("creature");
  const std::size_t n = 50000;
  std::vector<int> faces;
  sample_surface(mesh, n, &faces);
  ASSERT_EQ(faces.size(), n);
  EXPECT_TRUE(std::is_sorted(faces.begin(), faces.end()));
  const Eigen::VectorXd area = face_areas(mesh.V, mesh.F);
  std::vector<int> count(static_cast<std::size_t>(mesh.F.rows()), 0);
  for (const int f : faces) ++count[static_cast<std::size_t>(f)];
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    EXPECT_NEAR(count[static_cast<std::size_t>(f)], static_cast<double>(n) * area[f] / area.sum(), 1.0 + 1e-9) << f;
}

}  // namespace
}  // namespace meshmark
