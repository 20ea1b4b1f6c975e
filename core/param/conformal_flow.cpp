#include "core/param/conformal_flow.hpp"

#include <Eigen/CholmodSupport>
#include <cmath>
#include <stdexcept>

#include "core/mesh/massmatrix.hpp"
#include "core/param/normalize_mesh.hpp"
#include "core/util/input_error.hpp"

namespace meshmark {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Factor = Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>;
using Block = Eigen::MatrixXd;            // n×3: the three coordinates solved together
using Row3 = Eigen::Array<double, 1, 3>;  // one scalar per coordinate

Row3 column_dots(const Block& a, const Block& b) { return (a.array() * b.array()).colwise().sum(); }

// Solves A Y = B for three right-hand sides at once by conjugate gradients preconditioned with a
// (possibly stale) factor of A, starting from Y. False if the tolerance is not met in time.
bool preconditioned_cg(const SparseMatrix& A, const Factor& factor, const Block& B, Block& Y, double tolerance,
                       int max_iterations) {
  const Row3 b2 = B.colwise().squaredNorm().array().max(1e-300);
  Block R = B - A * Y;
  if (((R.colwise().squaredNorm().array() / b2).sqrt() < tolerance).all()) return true;
  Block Z = factor.solve(R);
  Block P = Z;
  Row3 rz = column_dots(R, Z);
  for (int k = 0; k < max_iterations; ++k) {
    const Block AP = A * P;
    const Row3 alpha = rz / column_dots(P, AP);
    Y.array() += P.array().rowwise() * alpha;
    R.array() -= AP.array().rowwise() * alpha;
    if (((R.colwise().squaredNorm().array() / b2).sqrt() < tolerance).all()) return true;
    Z = factor.solve(R);
    const Row3 rz_next = column_dots(R, Z);
    P = (Z.array() + P.array().rowwise() * (rz_next / rz)).matrix();
    rz = rz_next;
  }
  return false;
}

void factorize(Factor& factor, const SparseMatrix& A) {
  factor.factorize(A);
  if (factor.info() != Eigen::Success)
    throw InputError("the flow's linear system could not be factorized (degenerate triangles?)");
}

}  // namespace

double roundness(const Vertices& X, const Eigen::VectorXd& mass) {
  const Eigen::VectorXd r = X.rowwise().norm();
  const double total = mass.sum();
  const double mean = r.dot(mass) / total;
  return std::sqrt((r.array() - mean).square().matrix().dot(mass) / total) / mean;
}

ConformalFlowResult conformal_flow(const Vertices& V, const Faces& F, const ConformalFlowOptions& options,
                                   const JobControl* control) {
  SparseMatrix A = options.time_step * cotmatrix(V, F, options.stiffness);
  const Eigen::VectorXd stiffness_diagonal = A.diagonal();  // the pattern holds the diagonal

  Factor factor;
  factor.cholmod().nmethods = 1;  // AMD only: fast analysis, and the same ordering every run
  factor.cholmod().method[0].ordering = CHOLMOD_AMD;
  factor.analyzePattern(A);

  ConformalFlowResult result;
  result.X = V;
  Eigen::VectorXd mass = vertex_areas(result.X, F);
  for (result.iterations = 1; result.iterations <= options.max_iterations; ++result.iterations) {
    poll(control);
    A.diagonal() = stiffness_diagonal + mass;
    const Block rhs = mass.asDiagonal() * Block(result.X);
    Block Y = result.X;
    const bool solved = result.factorizations > 0 &&
                        preconditioned_cg(A, factor, rhs, Y, options.solve_tolerance, options.max_cg_iterations);
    if (!solved) {
      factorize(factor, A);
      ++result.factorizations;
      Y = factor.solve(rhs);
    }
    Vertices next = Y;
    result.X = apply(unit_area_normalization(next, F), next);
    mass = vertex_areas(result.X, F);
    result.roundness = roundness(result.X, mass);
    if (result.iterations >= options.min_iterations && result.roundness < options.roundness_tolerance) break;
  }
  result.iterations = std::min(result.iterations, options.max_iterations);
  return result;
}

}  // namespace meshmark
