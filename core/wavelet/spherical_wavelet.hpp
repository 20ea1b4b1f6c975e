#pragma once
// Spherical wavelets (Schröder and Sweldens 1995) on the nested grid, by lifting, in place.
//
// Going from level j+1 to level j, each vertex m born at level j+1 is first predicted from its
// stencil on level j (predict: γ_m = λ_m − Σ p_mk λ_k), then, in the lifted schemes, the
// level-j vertices are updated so that the wavelet has a vanishing moment
// (update: λ_v += s_vm γ_m for the edge ends v of m, s_vm = I_{j+1,m} / (2 I_{j,v}), I being
// the integrals of the scaling functions). After a forward transform to level j0 the signal's
// rows [0, V_j0) hold the coarse approximation and rows [V_j, V_j+1) the details of band j.
//
//   lazy               no prediction: details are the samples themselves
//   linear             predict from the edge ends (½, ½)
//   linear-lifting     linear + update
//   butterfly          predict with the 8-point butterfly (½, ⅛, −1/16)
//   butterfly-lifting  butterfly + update
//
// Each step is undone exactly by its inverse, so reconstruction is perfect up to round-off.

#include <string>
#include <vector>

#include "core/grid/sphere_grid.hpp"

namespace meshmark {

enum class WaveletType { lazy, linear, linear_lifting, butterfly, butterfly_lifting };
std::string to_string(WaveletType type);
/// "lazy", "linear", "linear-lifting", "butterfly", "butterfly-lifting"; throws std::invalid_argument.
WaveletType parse_wavelet_type(const std::string& name);

class SphericalWavelet {
 public:
  /// Prepares the transform of signals on the grid's level `finest` (V_finest rows).
  /// The grid must outlive this object.
  SphericalWavelet(const SphereGrid& grid, int finest, WaveletType type);

  int finest_level() const { return finest_; }
  WaveletType type() const { return type_; }
  int rows() const { return grid_.vertex_count(finest_); }

  /// Analysis: samples (rows() × C) → coefficients, finest level down to `coarsest`.
  void forward(Eigen::MatrixXd& signal, int coarsest = 0) const;
  /// Synthesis: coefficients → samples, `coarsest` up to the finest level.
  void inverse(Eigen::MatrixXd& coefficients, int coarsest = 0) const;
  /// The transpose of the synthesis: ⟨inverse(c), y⟩ = ⟨c, inverse_adjoint(y)⟩. Correlating
  /// samples with every synthesis basis function at once (the matched filter).
  void inverse_adjoint(Eigen::MatrixXd& samples, int coarsest = 0) const;

  /// ∫ of the scaling function of vertex k at level j (steradians): integrals()[j][k].
  const std::vector<Eigen::VectorXd>& integrals() const { return integrals_; }

 private:
  struct Weight {
    int vertex;
    double weight;
  };
  // Stencil weights of vertex m, in predict_[m - V_0] (empty for the lazy wavelet).
  std::vector<std::vector<Weight>> predict_;
  std::vector<std::array<double, 2>> update_;  // s for (v1, v2) of vertex m, at m - V_0
  void analyze_level(Eigen::MatrixXd& signal, int j) const;
  void synthesize_level(Eigen::MatrixXd& signal, int j) const;
  void adjoint_level(Eigen::MatrixXd& signal, int j) const;
  bool lifted() const { return type_ == WaveletType::linear_lifting || type_ == WaveletType::butterfly_lifting; }

  const SphereGrid& grid_;
  int finest_;
  WaveletType type_;
  std::vector<Eigen::VectorXd> integrals_;
};

/// ∫ of the finest-level hat functions: a third of the spherical area of each grid triangle
/// around the vertex (sums to 4π).
Eigen::VectorXd finest_integrals(const SphereGrid& grid, int level);

}  // namespace meshmark
