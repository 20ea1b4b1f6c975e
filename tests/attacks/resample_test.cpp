// The surface re-extracted from its signed distance field: closed, outward, every vertex new and
// within a grid step of the original, the volume kept, a surface with a hole capped and not
// doubled; impossible spacings are refused.

#include "core/attacks/resample.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "core/mesh/edge_incidence.hpp"
#include "core/spatial/aabb_tree.hpp"
#include "core/spatial/point_index.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

const Mesh& resample_subject() { return test::procedural_mesh("creature"); }

double diagonal_of(const Mesh& m) { return (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm(); }

double signed_volume(const Mesh& m) {
  double volume = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    volume += Eigen::Vector3d(m.V.row(m.F(f, 0)))
                  .dot(Eigen::Vector3d(m.V.row(m.F(f, 1))).cross(Eigen::Vector3d(m.V.row(m.F(f, 2))))) /
              6;
  return volume;
}

TEST(Resample, ExtractsAClosedOutwardSurfaceOfNewVerticesWithinAStep) {
  const double spacing = 0.01, step = spacing * diagonal_of(resample_subject());
  const Mesh out = resample_surface(resample_subject(), spacing);
  ASSERT_GT(out.F.rows(), 1000);
  const EdgeIncidence incidence = edge_incidence(out.F);
  for (std::size_t e = 0; e < incidence.face_count.size(); ++e) ASSERT_EQ(incidence.face_count[e], 2) << "edge " << e;
  EXPECT_NEAR(signed_volume(out) / signed_volume(resample_subject()), 1.0, 0.03);
  const AabbTree original(resample_subject().V, resample_subject().F);
  for (Eigen::Index v = 0; v < out.V.rows(); ++v)
    ASSERT_LT(std::sqrt(original.closest_point(out.V.row(v).transpose())->distance_squared), step) << "vertex " << v;
  const PointIndex new_vertices(out.V);
  Eigen::Index kept = 0;
  for (Eigen::Index v = 0; v < resample_subject().V.rows(); ++v)
    kept += new_vertices.nearest(resample_subject().V.row(v).transpose()).second < 1e-18;
  EXPECT_LT(kept, resample_subject().V.rows() / 100);
}

// The creature with its far end cut away (a wide hole): its open surface comes back as itself with the hole
// capped, not doubled by a sheet a band's width inside it (a flood fill finds no inside to a
// surface with a hole; the winding number does).
TEST(Resample, ASurfaceWithAHoleComesBackOnceWithTheHoleCapped) {
  const Mesh& closed = resample_subject();
  const double cut = closed.V.col(0).minCoeff() + 0.6 * (closed.V.col(0).maxCoeff() - closed.V.col(0).minCoeff());
  Mesh open{closed.V, Faces(0, 3)};
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f)
    if (closed.V(closed.F(f, 0), 0) < cut || closed.V(closed.F(f, 1), 0) < cut || closed.V(closed.F(f, 2), 0) < cut) {
      open.F.conservativeResize(open.F.rows() + 1, 3);
      open.F.row(open.F.rows() - 1) = closed.F.row(f);
    }
  ASSERT_LT(open.F.rows(), closed.F.rows());
  const double spacing = 0.01, step = spacing * diagonal_of(closed);
  const Mesh out = resample_surface(open, spacing);
  const EdgeIncidence incidence = edge_incidence(out.F);
  for (std::size_t e = 0; e < incidence.face_count.size(); ++e) ASSERT_EQ(incidence.face_count[e], 2) << "edge " << e;
  const AabbTree source(open.V, open.F), result(out.V, out.F);
  for (Eigen::Index f = 0; f < open.F.rows(); ++f)  // the open surface's vertices (its rim rounds off)
    for (int k = 0; k < 3; ++k)
      ASSERT_LT(std::sqrt(result.closest_point(open.V.row(open.F(f, k)).transpose())->distance_squared), 2 * step);
  Eigen::Index near_source = 0;
  for (Eigen::Index v = 0; v < out.V.rows(); ++v)
    near_source += std::sqrt(source.closest_point(out.V.row(v).transpose())->distance_squared) < step;
  EXPECT_GT(static_cast<double>(near_source), 0.9 * static_cast<double>(out.V.rows()));
}

TEST(Resample, RefusesSpacingsOutsideItsRange) {
  EXPECT_THROW(resample_surface(resample_subject(), 0.0001), std::invalid_argument);
  EXPECT_THROW(resample_surface(resample_subject(), 0.5), std::invalid_argument);
  EXPECT_THROW(resample_surface(Mesh{}, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark
