#include "core/watermark/nuisance_fields.hpp"

#include <algorithm>

#include <Eigen/Dense>

#include "core/mesh/laplacian_smooth.hpp"

namespace meshmark {

Eigen::MatrixXd nuisance_fields(const Mesh& original, const Vertices& normals, int threads) {
  const Eigen::Index n = original.V.rows();
  Eigen::MatrixXd fields(n, kNuisanceFieldCount);
  const Eigen::RowVector3d c = original.V.colwise().mean();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d v = (original.V.row(i) - c).transpose(), nv = normals.row(i).transpose();
    fields.block<1, 3>(i, 0) = nv.transpose();
    fields.block<1, 3>(i, 3) = v.cross(nv).transpose();
    fields(i, 6) = v.dot(nv);
  }
  const VertexNeighbors neighbors = vertex_neighbors(original.F, n);
  Vertices smoothed = original.V;
  int done = 0, column = 7;
  for (int iterations : kNuisanceSmoothingIterations) {
    smoothed = laplacian_smooth(smoothed, neighbors, kNuisanceSmoothingLambda, iterations - done, threads);
    done = iterations;
    fields.col(column++) = (smoothed - original.V).cwiseProduct(normals).rowwise().sum();
  }
  for (Eigen::Index k = 0; k < fields.cols(); ++k) {
    const double rms = fields.col(k).norm() / std::sqrt(static_cast<double>(n));
    if (rms > 0) fields.col(k) /= rms;
  }
  return fields;
}

const Eigen::MatrixXd& nuisance_fields(const PreparedModel& model, int threads) {
  std::call_once(model.nuisance->once,
                 [&] { model.nuisance->value = nuisance_fields(model.mesh, model.normals, threads); });
  return model.nuisance->value;
}

namespace {

// The least-squares coefficients of t by the columns of F, by the normal equations.
Eigen::VectorXd fit_coefficients(const Eigen::MatrixXd& F, const Eigen::VectorXd& t) {
  return (F.transpose() * F).completeOrthogonalDecomposition().solve(F.transpose() * t);
}

}  // namespace

void remove_fit(Eigen::VectorXd& t, const std::vector<char>& found, const Eigen::MatrixXd& fields) {
  if (std::all_of(found.begin(), found.end(), [](char f) { return f != 0; })) {  // a copy read in place
    t -= fields * fit_coefficients(fields, t);
    return;
  }
  // The found rows gathered once: the normal equations are then two matrix products (row by row
  // outer products of a column-major matrix were a twentieth of a daemon embed job).
  std::vector<Eigen::Index> rows;
  rows.reserve(static_cast<std::size_t>(t.size()));
  for (Eigen::Index i = 0; i < t.size(); ++i)
    if (found[static_cast<std::size_t>(i)]) rows.push_back(i);
  const Eigen::MatrixXd F = fields(rows, Eigen::all);
  t(rows) -= F * fit_coefficients(F, t(rows));
}

}  // namespace meshmark
