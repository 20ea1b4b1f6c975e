#include "core/watermark/prepared_model.hpp"

#include <chrono>

#include "core/mesh/mesh_digest.hpp"
#include "core/mesh/orientation.hpp"
#include "core/mesh/vertex_normals.hpp"
#include "core/param/massmatrix.hpp"

namespace meshmark {

namespace {

std::string refusal_text(const MeshReport& report) {
  std::string text = "the mesh cannot be watermarked:";
  for (const auto& p : report.problems) text += " " + p + ";";
  text.pop_back();
  return text;
}

int cap_level(BaseSolid base, Eigen::Index vertices) {
  int level = 5;
  while (level < 9 && sphere_grid_vertex_count(base, level) < 2 * vertices) ++level;
  return level;
}

}  // namespace

ModelRefused::ModelRefused(const MeshReport& r) : InputError(refusal_text(r)), report(r) {}

std::shared_ptr<const SphereGrid> GridCache::get(BaseSolid base, int levels) {
  std::lock_guard lock(mutex_);
  auto& slot = grids_[{static_cast<int>(base), levels}];
  if (auto grid = slot.lock()) return grid;
  auto grid = std::make_shared<const SphereGrid>(make_sphere_grid(base, levels));
  slot = grid;
  return grid;
}

PreparedModel prepare_model(const Mesh& mesh, const PrepareOptions& options, const JobControl* control,
                            GridCache* grids) {
  const auto start = std::chrono::steady_clock::now();
  PreparedModel model;
  checkpoint(control, "validate", 0.0);
  model.report = validate_mesh(mesh);
  if (!model.report.valid) throw ModelRefused(model.report);
  model.mesh = mesh;
  model.outward = orient_outward(mesh.V, mesh.F);
  model.digest = mesh_digest(mesh);
  model.normals = vertex_normals(mesh.V, model.outward);
  model.vertex_area = vertex_areas(mesh.V, model.outward);
  model.diagonal = model.report.bbox_diagonal;
  checkpoint(control, "parameterize", 0.05);
  SphereParamOptions param = options.param;
  param.stage = "parameterize";
  param.progress_from = 0.05;
  param.progress_to = 0.75;
  model.param = sphere_param(mesh, param, control);
  model.base = options.base;
  checkpoint(control, "sample", 0.75);

  SamplingOptions sampling = options.sampling;
  if (sampling.max_level < 0) sampling.max_level = cap_level(options.base, mesh.V.rows());
  sampling.start_level = std::min(sampling.start_level, sampling.max_level);
  model.grid = grids ? grids->get(options.base, sampling.max_level)
                     : std::make_shared<const SphereGrid>(make_sphere_grid(options.base, sampling.max_level));
  model.sampling = sample_on_grid(mesh.V, model.outward, model.param.S, *model.grid, sampling);
  model.sample_normals = interpolate_at(model.outward, model.sampling.samples, Eigen::MatrixXd(model.normals));
  model.sample_normals.rowwise().normalize();
  model.prepare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return model;
}

}  // namespace meshmark
