#include "core/watermark/vertex_field.hpp"

namespace meshmark {

Eigen::MatrixXd coefficients_to_vertices(const PreparedModel& model, const SphericalWavelet& wavelet,
                                         const Eigen::MatrixXd& coefficients) {
  Eigen::MatrixXd field = coefficients;
  wavelet.inverse(field);
  return interpolate_from_grid(*model.grid, model.level(), model.sampling.vertex_cells, field);
}

Eigen::MatrixXd vertices_to_coefficients(const PreparedModel& model, const SphericalWavelet& wavelet,
                                         const Eigen::MatrixXd& values) {
  const Faces& F = model.grid->faces[static_cast<std::size_t>(model.level())];
  Eigen::MatrixXd field = Eigen::MatrixXd::Zero(model.sample_count(), values.cols());
  const auto& cells = model.sampling.vertex_cells;
  for (std::size_t i = 0; i < cells.size(); ++i)  // Pᵀ: scatter with the interpolation weights
    for (int k = 0; k < 3; ++k) field.row(F(cells[i].face, k)) += cells[i].bary[k] * values.row(static_cast<Eigen::Index>(i));
  wavelet.inverse_adjoint(field);
  return field;
}

}  // namespace meshmark
