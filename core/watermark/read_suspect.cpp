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

// What every reading does to its raw offsets: the few far off clipped, the nuisance fields removed.
Displacement cleaned(const PreparedModel& model, Displacement d, const DisplacementOptions& options, int threads) {
  clip_outliers(d.t, d.found, options.outlier_clip_mads);
  remove_fit(d.t, d.found, nuisance_fields(model, threads));
  return d;
}

}  // namespace

Displacement read_suspect(const PreparedModel& model, const RegistrationTarget& target, const Mesh& aligned,
                          const DisplacementOptions& options, int threads) {
  return cleaned(
      model,
      measure_by_projection(target.tree, target.mesh, target.face_normals, aligned, model.diagonal, options, threads),
      options, threads);
}

Displacement read_at_vertices(const PreparedModel& model, const VertexOffsets& offsets,
                              const DisplacementOptions& options, int threads) {
  Displacement d;
  d.t = offsets.offset.cwiseProduct(model.normals).rowwise().sum();
  d.found = offsets.corresponded;
  d.missing = static_cast<std::size_t>(std::count(d.found.begin(), d.found.end(), 0));
  for (Eigen::Index v = 0; v < d.t.size(); ++v)
    if (!d.found[static_cast<std::size_t>(v)]) d.t[v] = 0;
  return cleaned(model, std::move(d), options, threads);
}

}  // namespace meshmark
