#pragma once
// The linear maps between wavelet coefficients on the grid and values at the mesh's vertices:
// D = P · S, where S is the wavelet synthesis on the grid and P interpolates grid values at each
// vertex's cell (its spherical image located in the grid). Embedding applies D; the matched
// filter of detection applies Dᵀ = Sᵀ · Pᵀ.

#include <Eigen/Core>

#include "core/wavelet/spherical_wavelet.hpp"
#include "core/watermark/prepared_model.hpp"

namespace meshmark {

/// D c: coefficients (V_J × C) → values at the vertices (#V × C).
Eigen::MatrixXd coefficients_to_vertices(const PreparedModel& model, const SphericalWavelet& wavelet,
                                         const Eigen::MatrixXd& coefficients);

/// Dᵀ u: values at the vertices (#V × C) → correlations with every basis function (V_J × C).
Eigen::MatrixXd vertices_to_coefficients(const PreparedModel& model, const SphericalWavelet& wavelet,
                                         const Eigen::MatrixXd& values);

}  // namespace meshmark
