#include "core/watermark/read_suspect.hpp"

#include <algorithm>
#include <cmath>

#include "core/watermark/nuisance_fields.hpp"

namespace meshmark {

namespace {

// Robust clipping at `mads` median absolute deviations (DisplacementOptions::outlier_clip_mads).
void clip_outliers(Eigen::VectorXd& t, const std::vector<char>& found, double mads) {
  std::vector<double> a;
  for (Eigen::Index i = 0; i < t.size(); ++i)
    if (found[i]) a.push_back(std::abs(t[i]));
  if (a.empty()) return;
  std::nth_element(a.begin(), a.begin() + static_cast<long>(a.size() / 2), a.end());
  const double limit = mads * a[a.size() / 2] / 0.6745;  // 0.6745: the MAD of a unit normal
  if (limit > 0) t = t.cwiseMax(-limit).cwiseMin(limit);
}

}  // namespace

Displacement read_suspect(const PreparedModel& model, const RegistrationTarget& target, const Mesh& aligned,
                          const DisplacementOptions& options, int threads) {
  Displacement d =
      measure_by_projection(target.tree, target.mesh, target.face_normals, aligned, model.diagonal, options, threads);
  clip_outliers(d.t, d.found, options.outlier_clip_mads);
  remove_fit(d.t, d.found, nuisance_fields(model, threads));
  return d;
}

}  // namespace meshmark
