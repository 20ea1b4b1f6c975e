#include "core/wavelet/spherical_wavelet.hpp"

#include <stdexcept>

#include "core/mesh/spherical_area.hpp"

namespace meshmark {

std::string to_string(WaveletType type) {
  switch (type) {
    case WaveletType::lazy:
      return "lazy";
    case WaveletType::linear:
      return "linear";
    case WaveletType::linear_lifting:
      return "linear-lifting";
    case WaveletType::butterfly:
      return "butterfly";
    case WaveletType::butterfly_lifting:
      return "butterfly-lifting";
  }
  return "linear-lifting";
}

WaveletType parse_wavelet_type(const std::string& name) {
  for (WaveletType t : {WaveletType::lazy, WaveletType::linear, WaveletType::linear_lifting, WaveletType::butterfly,
                        WaveletType::butterfly_lifting})
    if (name == to_string(t)) return t;
  throw std::invalid_argument("unknown wavelet '" + name +
                              "' (expected lazy, linear, linear-lifting, butterfly or butterfly-lifting)");
}

Eigen::VectorXd finest_integrals(const SphereGrid& grid, int level) {
  const Faces& F = grid.faces[static_cast<std::size_t>(level)];
  Eigen::VectorXd integral = Eigen::VectorXd::Zero(grid.vertex_count(level));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const double area =
        signed_spherical_area(grid.points.row(F(f, 0)), grid.points.row(F(f, 1)), grid.points.row(F(f, 2)));
    for (int k = 0; k < 3; ++k) integral[F(f, k)] += area / 3.0;
  }
  return integral;
}

SphericalWavelet::SphericalWavelet(const SphereGrid& grid, int finest, WaveletType type)
    : grid_(grid), finest_(finest), type_(type) {
  if (finest < 0 || finest > grid.levels)
    throw std::invalid_argument("wavelet level " + std::to_string(finest) + " is outside the grid's 0.." +
                                std::to_string(grid.levels));
  const int v0 = grid.vertex_count(0), n = grid.vertex_count(finest);
  predict_.resize(static_cast<std::size_t>(n - v0));
  for (int m = v0; m < n; ++m) {
    const Stencil& s = grid.stencil(m);
    auto& p = predict_[m - v0];
    if (type == WaveletType::linear || type == WaveletType::linear_lifting) p = {{s.v1, 0.5}, {s.v2, 0.5}};
    if (type == WaveletType::butterfly || type == WaveletType::butterfly_lifting)
      p = {{s.v1, 0.5},       {s.v2, 0.5},       {s.f1, 0.125},     {s.f2, 0.125},
           {s.e[0], -0.0625}, {s.e[1], -0.0625}, {s.e[2], -0.0625}, {s.e[3], -0.0625}};
  }
  // Integrals of the scaling functions: φ_{j,k} = φ_{j+1,k} + Σ_m p_mk φ_{j+1,m}.
  integrals_.resize(static_cast<std::size_t>(finest) + 1);
  integrals_[finest] = finest_integrals(grid, finest);
  for (int j = finest - 1; j >= 0; --j) {
    const Eigen::VectorXd& fine = integrals_[j + 1];
    Eigen::VectorXd coarse = fine.head(grid.vertex_count(j));
    for (int m = grid.vertex_count(j); m < grid.vertex_count(j + 1); ++m)
      for (const Weight& w : predict_[m - v0]) coarse[w.vertex] += w.weight * fine[m];
    integrals_[j] = std::move(coarse);
  }
  update_.resize(static_cast<std::size_t>(n - v0), {0.0, 0.0});
  if (lifted())
    for (int j = 0; j < finest; ++j)
      for (int m = grid.vertex_count(j); m < grid.vertex_count(j + 1); ++m) {
        const Stencil& s = grid.stencil(m);
        update_[m - v0] = {integrals_[j + 1][m] / (2 * integrals_[j][s.v1]),
                           integrals_[j + 1][m] / (2 * integrals_[j][s.v2])};
      }
}

namespace {

// Row operations on a column-major signal. One column (a field along the normal) is the common
// case, where Eigen's dynamic row blocks cost several times the arithmetic; the operations and
// their order are those of the row expressions, so results are bit for bit the same.
class SignalRows {
 public:
  explicit SignalRows(Eigen::MatrixXd& x) : data_(x.data()), rows_(x.rows()), cols_(x.cols()) {}
  // x(a) += w·x(b)
  void add(Eigen::Index a, double w, Eigen::Index b) const {
    for (Eigen::Index c = 0, o = 0; c < cols_; ++c, o += rows_) data_[a + o] += w * data_[b + o];
  }
  // x(a) -= w·x(b)
  void subtract(Eigen::Index a, double w, Eigen::Index b) const {
    for (Eigen::Index c = 0, o = 0; c < cols_; ++c, o += rows_) data_[a + o] -= w * data_[b + o];
  }
  // x(a) -= w1·x(b1) + w2·x(b2)
  void subtract2(Eigen::Index a, double w1, Eigen::Index b1, double w2, Eigen::Index b2) const {
    for (Eigen::Index c = 0, o = 0; c < cols_; ++c, o += rows_) data_[a + o] -= w1 * data_[b1 + o] + w2 * data_[b2 + o];
  }

 private:
  double* data_;
  Eigen::Index rows_, cols_;
};

}  // namespace

void SphericalWavelet::analyze_level(Eigen::MatrixXd& signal, int j) const {
  const int v0 = grid_.vertex_count(0), begin = grid_.vertex_count(j), end = grid_.vertex_count(j + 1);
  const SignalRows x(signal);
  for (int m = begin; m < end; ++m)
    for (const Weight& w : predict_[m - v0]) x.subtract(m, w.weight, w.vertex);
  if (!lifted()) return;
  for (int m = begin; m < end; ++m) {
    const Stencil& s = grid_.stencil(m);
    x.add(s.v1, update_[m - v0][0], m);
    x.add(s.v2, update_[m - v0][1], m);
  }
}

void SphericalWavelet::synthesize_level(Eigen::MatrixXd& signal, int j) const {
  const int v0 = grid_.vertex_count(0), begin = grid_.vertex_count(j), end = grid_.vertex_count(j + 1);
  const SignalRows x(signal);
  if (lifted())
    for (int m = end - 1; m >= begin; --m) {  // reverse order: undo the updates exactly
      const Stencil& s = grid_.stencil(m);
      x.subtract(s.v2, update_[m - v0][1], m);
      x.subtract(s.v1, update_[m - v0][0], m);
    }
  for (int m = begin; m < end; ++m)
    for (const Weight& w : predict_[m - v0]) x.add(m, w.weight, w.vertex);
}

void SphericalWavelet::adjoint_level(Eigen::MatrixXd& signal, int j) const {
  const int v0 = grid_.vertex_count(0), begin = grid_.vertex_count(j), end = grid_.vertex_count(j + 1);
  const SignalRows x(signal);
  for (int m = begin; m < end; ++m)  // transpose of the prediction: scatter to the stencil
    for (const Weight& w : predict_[m - v0]) x.add(w.vertex, w.weight, m);
  if (!lifted()) return;
  for (int m = begin; m < end; ++m) {  // transpose of the undone update
    const Stencil& s = grid_.stencil(m);
    x.subtract2(m, update_[m - v0][0], s.v1, update_[m - v0][1], s.v2);
  }
}

namespace {

void check_rows(const Eigen::MatrixXd& x, int rows) {
  if (x.rows() != rows)
    throw std::invalid_argument("a wavelet signal needs " + std::to_string(rows) + " rows, not " +
                                std::to_string(x.rows()));
}

}  // namespace

void SphericalWavelet::forward(Eigen::MatrixXd& signal, int coarsest) const {
  check_rows(signal, rows());
  for (int j = finest_ - 1; j >= coarsest; --j) analyze_level(signal, j);
}

void SphericalWavelet::inverse(Eigen::MatrixXd& coefficients, int coarsest) const {
  check_rows(coefficients, rows());
  for (int j = coarsest; j < finest_; ++j) synthesize_level(coefficients, j);
}

void SphericalWavelet::inverse_adjoint(Eigen::MatrixXd& samples, int coarsest) const {
  check_rows(samples, rows());
  for (int j = finest_ - 1; j >= coarsest; --j) adjoint_level(samples, j);
}

}  // namespace meshmark
