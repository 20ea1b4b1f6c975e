#include "core/registration/smooth_deformation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

int monomial_count(int degree) { return (degree + 1) * (degree + 2) * (degree + 3) / 6; }

// The monomials xᵃ yᵇ zᶜ with a + b + c ≤ degree, in a fixed order (1 first).
Eigen::VectorXd monomials(const Eigen::Vector3d& u, int degree) {
  Eigen::VectorXd out(monomial_count(degree));
  int k = 0;
  for (int total = 0; total <= degree; ++total)
    for (int a = total; a >= 0; --a)
      for (int b = total - a; b >= 0; --b)
        out[k++] = std::pow(u.x(), a) * std::pow(u.y(), b) * std::pow(u.z(), total - a - b);
  return out;
}

struct Correspondence {
  Eigen::Vector3d point, normal;
  double distance_squared;
  int face = -1;
};

// The closest point on the original of each deformed sample; `near` (the last step's, or empty)
// names a face near each, which bounds its search (the answer is the same).
std::vector<Correspondence> correspond(const Vertices& points, const SmoothDeformation& field, const AabbTree& tree,
                                       const Vertices& face_normals, const JobControl* control,
                                       const std::vector<Correspondence>& near = {}) {
  std::vector<Correspondence> out(static_cast<std::size_t>(points.rows()));
  parallel_for(points.rows(), threads_of(control), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      if ((i - begin) % 256 == 0) poll(control);
      const Eigen::Vector3d x = field.apply(points.row(i).transpose());
      const int hint = near.empty() ? -1 : near[static_cast<std::size_t>(i)].face;
      const TriangleHit hit = *tree.closest_point(x, std::numeric_limits<double>::infinity(), hint);
      out[static_cast<std::size_t>(i)] = {hit.point, face_normals.row(hit.face).transpose(), hit.distance_squared,
                                          hit.face};
    }
  });
  return out;
}

// The largest squared distance among the kept share of the correspondences.
double trim_cutoff(const std::vector<Correspondence>& matches, double trim) {
  std::vector<double> d2;
  for (const Correspondence& m : matches) d2.push_back(m.distance_squared);
  const auto keep = std::max<std::size_t>(1, static_cast<std::size_t>(trim * static_cast<double>(d2.size())));
  std::nth_element(d2.begin(), d2.begin() + static_cast<long>(keep - 1), d2.end());
  return d2[keep - 1];
}

double trimmed_rms(const std::vector<Correspondence>& matches, double cutoff) {
  double sum = 0;
  std::size_t kept = 0;
  for (const Correspondence& m : matches)
    if (m.distance_squared <= cutoff) sum += m.distance_squared, ++kept;
  return std::sqrt(sum / static_cast<double>(std::max<std::size_t>(kept, 1)));
}

// The coefficients minimizing the kept point-to-plane distances of the undeformed `points`
// displaced by the field, plus a small Tikhonov term.
Eigen::MatrixX3d solve_field(const Vertices& points, const std::vector<Correspondence>& matches, double cutoff,
                             const SmoothDeformation& shape, double regularization) {
  const int terms = monomial_count(shape.degree);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3 * terms, 3 * terms);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * terms);
  std::size_t kept = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Correspondence& m = matches[static_cast<std::size_t>(i)];
    if (m.distance_squared > cutoff) continue;
    const Eigen::Vector3d p = points.row(i).transpose();
    const Eigen::VectorXd basis = monomials((p - shape.centre) / shape.unit, shape.degree);
    Eigen::VectorXd row(3 * terms);  // coefficient (k, axis) at axis·terms + k, in diagonals
    for (int axis = 0; axis < 3; ++axis) row.segment(axis * terms, terms) = basis * m.normal[axis];
    A.selfadjointView<Eigen::Lower>().rankUpdate(row);
    b += row * (m.normal.dot(m.point - p) / shape.unit);
    ++kept;
  }
  A.triangularView<Eigen::Upper>() = A.transpose();
  A.diagonal().array() += regularization * static_cast<double>(kept);
  const Eigen::VectorXd solution = A.ldlt().solve(b) * shape.unit;
  Eigen::MatrixX3d coefficients(terms, 3);
  for (int axis = 0; axis < 3; ++axis) coefficients.col(axis) = solution.segment(axis * terms, terms);
  return coefficients;
}

}  // namespace

Eigen::Vector3d SmoothDeformation::apply(const Eigen::Vector3d& x) const {
  if (identity()) return x;
  return x + coefficients.transpose() * monomials((x - centre) / unit, degree);
}

Vertices SmoothDeformation::apply_to_rows(const Vertices& V) const {
  Vertices out(V.rows(), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) out.row(i) = apply(V.row(i).transpose()).transpose();
  return out;
}

namespace {

// ICP steps at `trial`'s degree from `fit`'s field: correspondences, then the field's least squares,
// while the trimmed RMS falls by more than 1 %. The field is fitted to more correspondences than the
// RMS counts (fit_trim): a bent part's far end is the last tenth to come close, and left out of
// the fit it came a little closer each step (a screwdriver bent by 20°: 29 steps at degree 2,
// stopped at 15 with 7 bits of 64 wrong).
void refine_field(const Vertices& points, const AabbTree& tree, const Vertices& face_normals,
                  const DeformationOptions& options, SmoothDeformation trial, DeformationFit& fit,
                  const JobControl* control) {
  std::vector<Correspondence> matches = correspond(points, fit.deformation, tree, face_normals, control);
  for (int step = 0; step < options.iterations; ++step) {
    trial.coefficients =
        solve_field(points, matches, trim_cutoff(matches, options.fit_trim), trial, options.regularization);
    matches = correspond(points, trial, tree, face_normals, control, matches);
    const double rms = trimmed_rms(matches, trim_cutoff(matches, options.trim));
    if (!(rms < fit.deformed_rms)) break;
    const bool settled = rms > 0.99 * fit.deformed_rms;
    fit.deformed_rms = rms;
    fit.deformation = trial;
    if (settled) break;
  }
}

}  // namespace

bool fits_much_better(const DeformationFit& fit, double diagonal, const DeformationOptions& options) {
  const double floor = options.min_rigid_rms * diagonal;
  const auto above_floor = [floor](double rms) { return std::sqrt(std::max(rms * rms - floor * floor, 0.0)); };
  return above_floor(fit.deformed_rms) < options.min_gain * above_floor(fit.rigid_rms);
}

DeformationFit fit_smooth_deformation(const Vertices& points, const AabbTree& tree, const Vertices& face_normals,
                                      double diagonal, const DeformationOptions& options, const JobControl* control) {
  DeformationFit fit;
  if (points.rows() < 3 * monomial_count(options.degree)) return fit;  // too few to fit a field
  SmoothDeformation field;
  field.centre = points.colwise().mean().transpose();
  field.unit = 0.5 * diagonal;  // the samples' coordinates within about ±1
  const std::vector<Correspondence> rigid = correspond(points, field, tree, face_normals, control);
  fit.rigid_rms = fit.deformed_rms = trimmed_rms(rigid, trim_cutoff(rigid, options.trim));
  // Coarse to fine: each degree starts from the correspondences of the one below, which a field
  // of all its terms at once, from the rigid pose's, can miss (a long limb bent ends far from
  // its place).
  for (int degree = 1; degree <= options.degree; ++degree) {
    field.degree = degree;
    refine_field(points, tree, face_normals, options, field, fit, control);
  }
  return fit;
}

}  // namespace meshmark
