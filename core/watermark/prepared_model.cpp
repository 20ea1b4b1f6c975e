#include "core/watermark/prepared_model.hpp"

#include <algorithm>
#include <chrono>
#include <future>

#include "core/mesh/fill_holes.hpp"
#include "core/mesh/mesh_digest.hpp"
#include "core/mesh/orient_patches.hpp"
#include "core/mesh/orientation.hpp"
#include "core/mesh/vertex_normals.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/watermark/nuisance_fields.hpp"

namespace meshmark {

namespace {

std::string refusal_text(const MeshReport& report) {
  std::string text = "the mesh cannot be watermarked:";
  for (const auto& p : report.problems) text += " " + p + ";";
  text.pop_back();
  return text;
}

int cap_level(const PrepareOptions& options, Eigen::Index vertices) {
  int level = options.sampling.start_level;
  while (level < options.max_grid_level && static_cast<double>(sphere_grid_vertex_count(options.base, level)) <
                                               options.grid_samples_per_vertex * static_cast<double>(vertices))
    ++level;
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

namespace {

// The spherical map of `surface` (the mesh, or the mesh with its holes closed), the grid and the
// samples; the mesh's own vertices are the first rows of `surface`.
void prepare_sphere(PreparedModel& model, const Mesh& surface, const Faces& surface_outward,
                    const PrepareOptions& options, const JobControl* control, GridCache* grids) {
  checkpoint(control, "parameterize", 0.05);
  SphereParamOptions param = options.param;
  param.stage = "parameterize";
  param.progress_from = 0.05;
  param.progress_to = 0.75;
  model.param = sphere_param(surface, param, control);
  model.base = options.base;
  checkpoint(control, "sample", 0.75);
  SamplingOptions sampling = options.sampling;
  if (sampling.max_level < 0) sampling.max_level = cap_level(options, surface.V.rows());
  sampling.start_level = std::min(sampling.start_level, sampling.max_level);
  model.grid = grids ? grids->get(options.base, sampling.max_level)
                     : std::make_shared<const SphereGrid>(make_sphere_grid(options.base, sampling.max_level));
  model.sampling =
      sample_on_grid(surface.V, surface_outward, model.param.S, *model.grid, sampling, threads_of(control));
  model.sampling.vertex_cells.resize(
      static_cast<std::size_t>(model.mesh.V.rows()));  // the filling's vertices carry nothing
}

}  // namespace

PreparedModel prepare_model(const Mesh& mesh, const PrepareOptions& options, const JobControl* control,
                            GridCache* grids) {
  const auto start = std::chrono::steady_clock::now();
  PreparedModel model;
  checkpoint(control, "validate", 0.0);
  model.report = validate_mesh(mesh, {.threads = threads_of(control)});
  if (!model.report.valid) throw ModelRefused(model.report);
  model.mesh = mesh;
  model.digest = mesh_digest(mesh);
  model.diagonal = model.report.bbox_diagonal;
  model.basis = model.report.basis;
  model.basis_reason = model.report.basis_reason;
  if (options.force_bumps && model.basis != MeshBasis::bumps) {
    model.basis = MeshBasis::bumps;
    model.basis_reason = "bumps asked for (the mesh would take the " + to_string(model.report.basis) + ")";
  }

  if (model.basis == MeshBasis::sphere_filled) {
    FilledHoles filled = fill_holes(mesh);
    const MeshReport closed = validate_mesh(filled.mesh, {.threads = threads_of(control)});
    if (closed.closed_genus_zero) {
      model.filled.V = filled.mesh.V;
      model.filled.F = orient_outward(filled.mesh.V, filled.mesh.F);
    } else {  // closing the holes did not give a sphere-like surface: bumps after all
      model.basis = MeshBasis::bumps;
      model.basis_reason = "closing the holes did not give one closed genus-0 surface (" +
                           (closed.sphere_problems.empty() ? std::string("?") : closed.sphere_problems.front()) +
                           "): multiscale bumps on the mesh itself";
    }
  }
  switch (model.basis) {
    case MeshBasis::sphere:
      model.outward = orient_outward(mesh.V, mesh.F);
      break;
    case MeshBasis::sphere_filled:
      model.outward = model.filled.F.topRows(mesh.F.rows());
      break;
    default:
      model.outward = orient_patches(mesh.V, mesh.F).faces;
      break;
  }
  model.normals = vertex_normals(mesh.V, model.outward);
  model.vertex_area = vertex_areas(mesh.V, model.outward);
  // Detection's nuisance fields need only the mesh and its normals: made on one thread while the
  // basis is built (the parameterization's coarsening is serial and leaves the others idle).
  std::future<void> nuisance;
  if (threads_of(control) > 1) nuisance = std::async(std::launch::async, [&model] { nuisance_fields(model, 1); });

  if (model.basis == MeshBasis::sphere) prepare_sphere(model, mesh, model.outward, options, control, grids);
  else if (model.basis == MeshBasis::sphere_filled)
    prepare_sphere(model, model.filled, model.filled.F, options, control, grids);
  else {
    checkpoint(control, "basis", 0.05);
    model.bump_options = options.bumps;
    model.bump_options.min_component_vertices =  // a low-poly model's small parts carry it too
        std::min(options.bumps.min_component_vertices, static_cast<int>(model.report.marked_component_floor));
    model.bumps = std::make_shared<const BumpBasis>(multiscale_bumps(mesh, model.bump_options, control));
  }
  if (nuisance.valid()) nuisance.get();
  model.prepare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return model;
}

}  // namespace meshmark
