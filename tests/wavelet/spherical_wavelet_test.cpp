#include "core/wavelet/spherical_wavelet.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/grid/sample_on_grid.hpp"
#include "core/param/sphere_param.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

const WaveletType kAll[] = {WaveletType::lazy, WaveletType::linear, WaveletType::linear_lifting, WaveletType::butterfly,
                            WaveletType::butterfly_lifting};
const WaveletType kPredicting[] = {WaveletType::linear, WaveletType::linear_lifting, WaveletType::butterfly,
                                   WaveletType::butterfly_lifting};

Eigen::MatrixXd random_signal(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd x(rows, cols);
  for (int i = 0; i < x.size(); ++i) x.data()[i] = u(rng);
  return x;
}

TEST(SphericalWavelet, ReconstructsRandomSignalsPerfectlyOnEveryBaseLevelAndScheme) {
  for (BaseSolid base : kBaseSolids) {
    const SphereGrid grid = make_sphere_grid(base, 6);
    for (int level : {2, 4, 6})
      for (WaveletType type : kAll) {
        const SphericalWavelet w(grid, level, type);
        const Eigen::MatrixXd x = random_signal(w.rows(), 3, 11 + level);
        Eigen::MatrixXd c = x;
        w.forward(c);
        if (type != WaveletType::lazy) {
          EXPECT_GT((c - x).norm(), 0.0);  // it did something
        }
        w.inverse(c);
        EXPECT_LT((c - x).cwiseAbs().maxCoeff(), 1e-13) << to_string(base) << " " << level << " " << to_string(type);
      }
  }
}

TEST(SphericalWavelet, ReconstructsToAnyCoarsestLevel) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::icosahedron, 5);
  const SphericalWavelet w(grid, 5, WaveletType::butterfly_lifting);
  const Eigen::MatrixXd x = random_signal(w.rows(), 1, 3);
  for (int coarsest = 0; coarsest <= 5; ++coarsest) {
    Eigen::MatrixXd c = x;
    w.forward(c, coarsest);
    w.inverse(c, coarsest);
    EXPECT_LT((c - x).cwiseAbs().maxCoeff(), 1e-13);
  }
}

TEST(SphericalWavelet, ConstantSignalHasZeroDetails) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::tetrahedron, 6);
  for (WaveletType type : kPredicting) {
    const SphericalWavelet w(grid, 6, type);
    Eigen::MatrixXd c = Eigen::MatrixXd::Constant(w.rows(), 2, 3.25);
    w.forward(c);
    EXPECT_LT(c.bottomRows(w.rows() - grid.vertex_count(0)).cwiseAbs().maxCoeff(), 1e-13) << to_string(type);
    EXPECT_LT((c.topRows(grid.vertex_count(0)).array() - 3.25).abs().maxCoeff(), 1e-13) << to_string(type);
  }
}

TEST(SphericalWavelet, LiftedSchemesPreserveTheIntegralWeightedMeanLevelToLevel) {
  for (BaseSolid base : kBaseSolids) {
    const SphereGrid grid = make_sphere_grid(base, 5);
    for (WaveletType type : {WaveletType::linear_lifting, WaveletType::butterfly_lifting}) {
      const SphericalWavelet w(grid, 5, type);
      const Eigen::MatrixXd x = random_signal(w.rows(), 1, 5);
      const double integral = w.integrals()[5].dot(x.col(0));
      for (int coarsest = 4; coarsest >= 0; --coarsest) {
        Eigen::MatrixXd c = x;
        w.forward(c, coarsest);
        const int n = grid.vertex_count(coarsest);
        EXPECT_NEAR(w.integrals()[coarsest].dot(c.col(0).head(n)), integral, 1e-12)
            << to_string(base) << " " << to_string(type) << " level " << coarsest;
      }
    }
  }
}

TEST(SphericalWavelet, UnliftedSchemesDoNotPreserveTheMean) {
  // The check above would pass vacuously if the update did nothing; without it the mean drifts.
  const SphereGrid grid = make_sphere_grid(BaseSolid::tetrahedron, 5);
  const SphericalWavelet w(grid, 5, WaveletType::linear);
  const Eigen::MatrixXd x = random_signal(w.rows(), 1, 5);
  Eigen::MatrixXd c = x;
  w.forward(c, 0);
  EXPECT_GT(std::abs(w.integrals()[0].dot(c.col(0).head(4)) - w.integrals()[5].dot(x.col(0))), 1e-3);
}

TEST(SphericalWavelet, IntegralsSumToTheSphereAreaAtEveryLevel) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::octahedron, 5);
  for (WaveletType type : kPredicting) {  // predictions sum to 1, so no mass is lost
    const SphericalWavelet w(grid, 5, type);
    for (int j = 0; j <= 5; ++j) EXPECT_NEAR(w.integrals()[j].sum(), 4 * M_PI, 1e-11) << to_string(type) << " " << j;
  }
}

TEST(SphericalWavelet, InverseAdjointIsTheTransposeOfTheInverse) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::icosahedron, 4);
  for (WaveletType type : kAll) {
    const SphericalWavelet w(grid, 4, type);
    Eigen::MatrixXd c = random_signal(w.rows(), 1, 21), y = random_signal(w.rows(), 1, 22);
    Eigen::MatrixXd sc = c, sty = y;
    w.inverse(sc);
    w.inverse_adjoint(sty);
    EXPECT_NEAR(sc.col(0).dot(y.col(0)), c.col(0).dot(sty.col(0)), 1e-10) << to_string(type);
  }
}

TEST(SphericalWavelet, LinearPredictionIsExactForLinearFunctionsOnTheFlatEdge) {
  // A vertex's linear prediction is its edge ends' mean: exact for the chordal midpoint, so the
  // detail of a linear function of the position is the function of (m − (v1+v2)/2).
  const SphereGrid grid = make_sphere_grid(BaseSolid::tetrahedron, 3);
  const SphericalWavelet w(grid, 3, WaveletType::linear);
  Eigen::MatrixXd x = grid.points;
  w.forward(x, 2);
  for (int m = grid.vertex_count(2); m < grid.vertex_count(3); ++m) {
    const Stencil& s = grid.stencil(m);
    const Eigen::RowVector3d expected = grid.points.row(m) - 0.5 * (grid.points.row(s.v1) + grid.points.row(s.v2));
    EXPECT_LT((x.row(m) - expected).norm(), 1e-15);
  }
}

TEST(SphericalWavelet, ReconstructsSampledMeshesExactly) {
  const Mesh& mesh = test::procedural_mesh("creature");
  const SphereParam p = sphere_param(mesh);
  for (BaseSolid base : kBaseSolids) {
    const SphereGrid grid = make_sphere_grid(base, 6);
    SamplingOptions options;
    options.start_level = options.max_level = 6;
    const GridSampling sampling = sample_on_grid(mesh.V, p.F, p.S, grid, options);
    for (WaveletType type : kAll) {
      const SphericalWavelet w(grid, 6, type);
      Eigen::MatrixXd c = sampling.positions;
      w.forward(c);
      w.inverse(c);
      EXPECT_LT((c - sampling.positions).cwiseAbs().maxCoeff(), 1e-12) << to_string(base) << " " << to_string(type);
    }
  }
}

TEST(SphericalWavelet, RefusesASignalOfTheWrongSize) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::tetrahedron, 3);
  const SphericalWavelet w(grid, 3, WaveletType::linear);
  Eigen::MatrixXd x(10, 3);
  EXPECT_THROW(w.forward(x), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark
