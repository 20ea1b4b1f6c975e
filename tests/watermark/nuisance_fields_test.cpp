// Removing the nuisance fields' fit: what is left is orthogonal to every field where measured,
// any mix of the fields added before changes nothing, and what was not measured is untouched.

#include "core/watermark/nuisance_fields.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace meshmark {
namespace {

TEST(RemoveFit, LeavesWhatIsOrthogonalToTheFieldsWhereMeasuredAndTouchesNothingElse) {
  const Eigen::Index n = 500;
  Eigen::MatrixXd fields(n, 3);
  Eigen::VectorXd t(n);
  std::vector<char> found(static_cast<std::size_t>(n), 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) / n;
    fields.row(i) << 1.0, x, x * x;
    t[i] = std::sin(40.0 * x) + 3.0 - 2.0 * x;
    if (i % 7 == 0) found[static_cast<std::size_t>(i)] = 0, t[i] = 5.0;  // erasures keep their value
  }
  Eigen::VectorXd left = t;
  remove_fit(left, found, fields);
  Eigen::VectorXd shifted = t + fields * Eigen::Vector3d(0.5, -4.0, 2.0);
  for (Eigen::Index i = 0; i < n; ++i)
    if (!found[static_cast<std::size_t>(i)]) shifted[i] = 5.0;
  remove_fit(shifted, found, fields);
  for (Eigen::Index k = 0; k < fields.cols(); ++k) {
    double dot = 0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (found[static_cast<std::size_t>(i)]) dot += fields(i, k) * left[i];
    EXPECT_NEAR(dot, 0.0, 1e-9) << "field " << k;
  }
  EXPECT_LT((shifted - left).cwiseAbs().maxCoeff(), 1e-9);
  for (Eigen::Index i = 0; i < n; i += 7) EXPECT_EQ(left[i], 5.0);
}

TEST(RemoveFit, NothingMeasuredChangesNothing) {
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(10, 0.0, 1.0);
  const Eigen::VectorXd before = t;
  remove_fit(t, std::vector<char>(10, 0), Eigen::MatrixXd::Ones(10, 2));
  EXPECT_EQ(t, before);
}

}  // namespace
}  // namespace meshmark
