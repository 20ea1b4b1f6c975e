// The carrier estimator against a dense solve of the same normal equations.

#include "core/watermark/carrier_estimate.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace meshmark {
namespace {

struct DenseProblem {
  Eigen::MatrixXd A;  // vertices × carriers
  Eigen::VectorXd t;
};

DenseProblem problem() {
  std::srand(7);
  DenseProblem p{Eigen::MatrixXd::Random(60, 12), Eigen::VectorXd::Random(60)};
  return p;
}

CarrierEstimator estimator_of(const Eigen::MatrixXd& A) {
  return CarrierEstimator([A](const Eigen::VectorXd& s) -> Eigen::VectorXd { return A * s; },
                          [A](const Eigen::VectorXd& t) -> Eigen::VectorXd { return A.transpose() * t; }, A.cols());
}

TEST(CarrierEstimate, TheMatchedFilterIsTheAdjointApplied) {
  const DenseProblem p = problem();
  const CarrierEstimator e = estimator_of(p.A);
  EXPECT_LT((e.matched(p.t) - p.A.transpose() * p.t).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(e.estimate(e.matched(p.t), 0.0), e.matched(p.t)) << "relative 0 is the matched filter itself";
}

TEST(CarrierEstimate, TheRegularizedEstimateSolvesTheNormalEquations) {
  const DenseProblem p = problem();
  const CarrierEstimator e = estimator_of(p.A);
  const Eigen::MatrixXd gram = p.A.transpose() * p.A;
  // The probe's d is near the true mean of diag(AᵀA) on a dense random A.
  EXPECT_NEAR(e.regularization(1.0) / gram.diagonal().mean(), 1.0, 0.5);
  for (double relative : {1.0, 0.1}) {
    const double mu = e.regularization(relative);
    const Eigen::VectorXd dense = (gram + mu * Eigen::MatrixXd::Identity(12, 12)).ldlt().solve(p.A.transpose() * p.t);
    const Eigen::VectorXd ours = e.estimate(e.matched(p.t), relative);
    EXPECT_LT((ours - dense).norm(), 1e-2 * dense.norm()) << "relative " << relative;
  }
}

// Every shift of one multi-shift solve meets its own normal equations, as a solve of its own does,
// in the order asked, and a zero stays the matched filter.
TEST(CarrierEstimate, OneMultiShiftSolveMeetsEveryShiftsNormalEquations) {
  const DenseProblem p = problem();
  const CarrierEstimator e = estimator_of(p.A);
  const Eigen::MatrixXd gram = p.A.transpose() * p.A;
  const std::vector<double> relatives{1.0, 0.0, 0.01, 0.1, 10.0};
  const std::vector<Eigen::VectorXd> all = e.estimates(e.matched(p.t), relatives);
  ASSERT_EQ(all.size(), relatives.size());
  EXPECT_EQ(all[1], e.matched(p.t));
  for (std::size_t i = 0; i < relatives.size(); ++i) {
    if (relatives[i] == 0) continue;
    const double mu = e.regularization(relatives[i]);
    const Eigen::VectorXd dense = (gram + mu * Eigen::MatrixXd::Identity(12, 12)).ldlt().solve(p.A.transpose() * p.t);
    EXPECT_LT((all[i] - dense).norm(), 1e-2 * dense.norm()) << "relative " << relatives[i];
    EXPECT_LT((all[i] - e.estimate(e.matched(p.t), relatives[i])).norm(), 2e-2 * dense.norm());
  }
}

TEST(CarrierEstimate, IsLinearInTheMeasurement) {
  const DenseProblem p = problem();
  const CarrierEstimator e = estimator_of(p.A);
  const Eigen::VectorXd once = e.estimate(e.matched(p.t), 1.0);
  const Eigen::VectorXd twice = e.estimate(e.matched(2.0 * p.t), 1.0);
  EXPECT_LT((twice - 2.0 * once).norm(), 1e-3 * once.norm());
}

// Two groups of carriers a thousand times apart in scale: preconditioned by group, as many steps
// as unknowns solve what plain conjugate gradients, in rounding, leave far from the solution.
TEST(CarrierEstimate, GroupsOfVeryDifferentScaleConvergeWhenPreconditioned) {
  DenseProblem p = problem();
  p.A.leftCols(6) *= 1000.0;
  const Eigen::MatrixXd gram = p.A.transpose() * p.A;
  const std::vector<int> groups{0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1};
  const CarrierSolveOptions steps{12, 0.0};  // as many as unknowns: exact, were it not for rounding
  auto forward = [A = p.A](const Eigen::VectorXd& s) -> Eigen::VectorXd { return A * s; };
  auto adjoint = [A = p.A](const Eigen::VectorXd& t) -> Eigen::VectorXd { return A.transpose() * t; };
  const CarrierEstimator grouped(forward, adjoint, 12, steps, groups), plain(forward, adjoint, 12, steps);
  const double relative = 1e-9;
  const Eigen::VectorXd exact =
      (gram + grouped.regularization(relative) * Eigen::MatrixXd::Identity(12, 12)).ldlt().solve(p.A.transpose() * p.t);
  const Eigen::VectorXd ours = grouped.estimate(grouped.matched(p.t), relative);
  EXPECT_LT((ours - exact).norm(), 1e-10 * exact.norm());
  const Eigen::VectorXd unconditioned = plain.estimate(plain.matched(p.t), relative);
  EXPECT_GT((unconditioned - exact).norm(), 1e-3 * exact.norm());
}

TEST(CarrierEstimate, EachEstimateTriedCostsItsBits) {
  EXPECT_EQ(bits_for_tries(1), 0);
  EXPECT_EQ(bits_for_tries(2), 1);
  EXPECT_EQ(bits_for_tries(6), 3);
}

}  // namespace
}  // namespace meshmark
