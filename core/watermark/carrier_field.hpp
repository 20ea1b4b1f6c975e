#pragma once
// The spread scheme's carriers, whatever basis a prepared model has, and the linear maps between
// their amplitudes and the normal displacement at the original's vertices:
//   sphere  D = P · S: the wavelet synthesis S on the grid, then P interpolating grid values at
//           each vertex's cell (its spherical image located in the grid); Dᵀ = Sᵀ · Pᵀ;
//   bumps   D = B, the bumps' values at the vertices; Dᵀ = Bᵀ.
// A coefficient signal has one entry per grid vertex (sphere) or per bump; bands group them,
// coarse to fine.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "core/wavelet/spherical_wavelet.hpp"
#include "core/watermark/prepared_model.hpp"

namespace meshmark {

struct CarrierBand {
  int label = 0;             ///< grid level (sphere) or bump band (bumps), for reports
  std::vector<int> members;  ///< the coefficients that may carry (sphere-filled: not those on the filling)
  double support = 0;        ///< mean number of mesh vertices one basis function of the band covers
};

class CarrierField {
 public:
  /// to_vertices runs on `threads` threads (0: the hardware's).
  CarrierField(const PreparedModel& model, WaveletType wavelet, int threads);

  Eigen::Index size() const { return size_; }
  const std::vector<CarrierBand>& bands() const { return bands_; }

  /// D c: coefficients (size() × C) → values at the vertices (#V × C).
  Eigen::MatrixXd to_vertices(const Eigen::MatrixXd& coefficients) const;
  /// Dᵀ u: values at the vertices (#V × C) → correlations with every basis function (size() × C).
  Eigen::MatrixXd from_vertices(const Eigen::MatrixXd& values) const;

  /// Per coefficient: the original's roughness under it, relative to its band's median,
  /// square-rooted and kept within [0.5, 2] (the paper's masking idea); 1 outside `bands`.
  Eigen::VectorXd relative_roughness(const std::vector<int>& bands) const;

 private:
  const PreparedModel& model_;
  int threads_;
  std::optional<SphericalWavelet> wavelet_;
  Eigen::Index size_ = 0;
  std::vector<CarrierBand> bands_;
};

}  // namespace meshmark
