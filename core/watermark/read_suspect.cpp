#include "core/watermark/read_suspect.hpp"

#include <algorithm>
#include <cmath>

#include "core/watermark/nuisance_fields.hpp"

namespace meshmark {

namespace {

// Robust clipping at 6 median absolute deviations: a few readings off the surface (the far side
// of a thin part) must not outweigh thousands.
void clip_outliers(Eigen::VectorXd& t, const std::vector<char>& found) {
  std::vector<double> a;
  for (Eigen::Index i = 0; i < t.size(); ++i)
    if (found[i]) a.push_back(std::abs(t[i]));
  if (a.empty()) return;
  std::nth_element(a.begin(), a.begin() + static_cast<long>(a.size() / 2), a.end());
  const double limit = 6 * a[a.size() / 2] / 0.6745;
  if (limit > 0) t = t.cwiseMax(-limit).cwiseMin(limit);
}

}  // namespace

Displacement read_suspect(const PreparedModel& model, const RegistrationTarget& target, const Mesh& aligned,
                          const DisplacementOptions& options) {
  Displacement d;
  if (options.method == ReadingMethod::projection) {
    d = measure_by_projection(target.tree, model.mesh, target.face_normals, aligned, model.diagonal, options);
  } else {
    const AabbTree tree(aligned.V, aligned.F);
    d = measure_displacement(tree, model.mesh.V, model.normals, model.diagonal, options);
  }
  clip_outliers(d.t, d.found);
  remove_fit(d.t, d.found, nuisance_fields(model));
  return d;
}

}  // namespace meshmark
