#pragma once
// Fields on the original's vertices that an attack or the registration can add to the measured
// normal displacement, but that carry no watermark: the seven of a small rigid motion plus scale
// (translation n, rotation (v − c) × n, scale (v − c)·n) and the shrinkage Laplacian smoothing
// causes at three scales. Detection removes their least-squares fit before filtering; they do
// not depend on the key, so the false-alarm bound still holds.

#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/watermark/prepared_model.hpp"

namespace meshmark {

/// The smoothing whose shrinkage is modelled: the benchmark's λ, and the iteration counts of the
/// three scales (cumulative). The fields are kept with the prepared model, so these are fixed.
inline constexpr double kNuisanceSmoothingLambda = 0.03;
inline constexpr int kNuisanceSmoothingIterations[] = {10, 30, 100};

inline constexpr Eigen::Index kNuisanceFieldCount = 10;

/// #V × kNuisanceFieldCount fields, each column scaled to unit RMS; smoothed on `threads` threads
/// (0: the hardware's).
Eigen::MatrixXd nuisance_fields(const Mesh& original, const Vertices& normals, int threads);

/// The model's nuisance fields, computed on first use (on `threads` threads) and kept with the
/// model (and in its file, prepared_model_io.hpp).
const Eigen::MatrixXd& nuisance_fields(const PreparedModel& model, int threads);

/// t minus its least-squares fit by the columns of `fields`, over the entries where `found`.
void remove_fit(Eigen::VectorXd& t, const std::vector<char>& found, const Eigen::MatrixXd& fields);

}  // namespace meshmark
