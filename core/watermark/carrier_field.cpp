#include "core/watermark/carrier_field.hpp"

#include <algorithm>
#include <cmath>

namespace meshmark {

CarrierField::CarrierField(const PreparedModel& model, WaveletType wavelet, int threads)
    : model_(model), threads_(threads) {
  const double vertices = static_cast<double>(model.mesh.V.rows());
  if (model.basis == MeshBasis::bumps) {
    size_ = model.bumps->values.cols();
    bands_.resize(static_cast<std::size_t>(model.bumps->bands()));
    for (int b = 0; b < model.bumps->bands(); ++b) {
      bands_[static_cast<std::size_t>(b)].label = b;
      bands_[static_cast<std::size_t>(b)].support = model.bumps->band_support[static_cast<std::size_t>(b)];
    }
    for (std::size_t k = 0; k < model.bumps->band.size(); ++k)
      bands_[static_cast<std::size_t>(model.bumps->band[k])].members.push_back(static_cast<int>(k));
    return;
  }
  wavelet_.emplace(*model.grid, model.level(), wavelet);
  size_ = model.sample_count();
  // On a filled sphere, coefficients whose grid vertex lies on the filling carry nothing real.
  const auto real = [&](int k) {
    return model.filled.F.rows() == 0 || model.sampling.samples[static_cast<std::size_t>(k)].face < model.mesh.F.rows();
  };
  for (int level = 1; level <= model.level(); ++level) {
    CarrierBand band;
    band.label = level;
    band.support = 3.0 * vertices / model.grid->vertex_count(level);  // a hat covers ~3 vertices' share
    for (int k = model.grid->vertex_count(level - 1); k < model.grid->vertex_count(level); ++k)
      if (real(k)) band.members.push_back(k);
    bands_.push_back(std::move(band));
  }
}

Eigen::MatrixXd CarrierField::to_vertices(const Eigen::MatrixXd& coefficients) const {
  if (!wavelet_) return model_.bumps->values * coefficients;
  Eigen::MatrixXd field = coefficients;
  wavelet_->inverse(field);
  return interpolate_from_grid(*model_.grid, model_.level(), model_.sampling.vertex_cells, field, threads_);
}

Eigen::MatrixXd CarrierField::from_vertices(const Eigen::MatrixXd& values) const {
  if (!wavelet_) return model_.bumps->values.transpose() * values;
  const Faces& F = model_.grid->faces[static_cast<std::size_t>(model_.level())];
  Eigen::MatrixXd field = Eigen::MatrixXd::Zero(model_.sample_count(), values.cols());
  const auto& cells = model_.sampling.vertex_cells;
  for (std::size_t i = 0; i < cells.size(); ++i)  // Pᵀ: scatter with the interpolation weights
    for (int k = 0; k < 3; ++k)
      field.row(F(cells[i].face, k)) += cells[i].bary[k] * values.row(static_cast<Eigen::Index>(i));
  wavelet_->inverse_adjoint(field);
  return field;
}

Eigen::VectorXd CarrierField::relative_roughness(const std::vector<int>& bands) const {
  // Raw roughness: the size of the geometry's detail coefficient (sphere), or the mean umbrella
  // offset under the bump (bumps).
  Eigen::VectorXd raw(size_);
  if (wavelet_) {
    Eigen::MatrixXd geometry = model_.sampling.positions;
    wavelet_->forward(geometry);
    raw = geometry.rowwise().norm();
  } else {
    raw = Eigen::Map<const Eigen::VectorXd>(model_.bumps->roughness.data(), size_);
  }
  Eigen::VectorXd r = Eigen::VectorXd::Ones(size_);
  for (const int b : bands) {
    const auto& members = bands_[static_cast<std::size_t>(b)].members;
    if (members.empty()) continue;
    std::vector<double> sorted;
    for (const int k : members) sorted.push_back(raw[k]);
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double median = std::max(sorted[sorted.size() / 2], 1e-300);
    for (const int k : members) r[k] = std::clamp(std::sqrt(raw[k] / median), 0.5, 2.0);
  }
  return r;
}

}  // namespace meshmark
