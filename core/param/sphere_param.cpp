#include "core/param/sphere_param.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/mesh/orientation.hpp"
#include "core/mesh/spherical_area.hpp"
#include "core/param/check_spherical_map.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/param/normalize_mesh.hpp"

namespace meshmark {

namespace {

Vertices project_to_sphere(const Vertices& X) { return X.rowwise().normalized(); }

}  // namespace

AreaDistortion area_distortion(const Vertices& V, const Vertices& S, const Faces& F) {
  const Eigen::VectorXd surface = face_areas(V, F);
  const double total = surface.sum();
  std::vector<double> ratio(static_cast<std::size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const double sphere = signed_spherical_area(S.row(F(f, 0)), S.row(F(f, 1)), S.row(F(f, 2))) / (4 * M_PI);
    ratio[f] = sphere / (surface[f] / total);
  }
  std::sort(ratio.begin(), ratio.end());
  auto at = [&](double q) { return ratio[static_cast<std::size_t>(q * static_cast<double>(ratio.size() - 1))]; };
  return {ratio.front(), at(0.05), at(0.5), at(0.95), ratio.back()};
}

std::string to_string(SphereMethod method) {
  return method == SphereMethod::progressive ? "progressive" : "conformal-flow";
}

SphereMethod parse_sphere_method(const std::string& name) {
  if (name == "progressive") return SphereMethod::progressive;
  if (name == "conformal-flow") return SphereMethod::conformal_flow;
  throw std::invalid_argument("unknown parameterization method '" + name +
                              "' (expected progressive or conformal-flow)");
}

namespace {

// The conformal flow, projected, centred and repaired where it folded; S in `result`.
void conformal_map(const Vertices& X0, const SphereParamOptions& options, const JobControl* control,
                   SphereParam& result) {
  const ConformalFlowResult flow = conformal_flow(X0, result.F, options.flow, control);
  result.flow_iterations = flow.iterations;
  result.factorizations = flow.factorizations;
  result.S = project_to_sphere(flow.X);
  mobius_center(result.S, vertex_areas(X0, result.F), options.centering);
  const SphericalMapCheck check = check_spherical_map(result.S, result.F);
  result.flipped_before_repair = check.flipped_faces;
  if (check.flipped_faces > 0) result.repair_rounds = repair_spherical_flips(result.S, result.F, options.repair).rounds;
}

}  // namespace

SphereParam sphere_param(const Mesh& mesh, const SphereParamOptions& options, const JobControl* control) {
  const auto start = std::chrono::steady_clock::now();
  SphereParam result;
  result.method = options.method;
  result.F = orient_outward(mesh.V, mesh.F);
  result.flipped_input = result.F(0, 1) != mesh.F(0, 1);
  const Vertices X0 = apply(unit_area_normalization(mesh.V, result.F), mesh.V);
  // The map takes most of the stage's progress, the area correction the rest.
  const double span = options.progress_to - options.progress_from;
  const bool equalize = options.equalize_area.value_or(options.method == SphereMethod::conformal_flow);
  const double map_end = options.progress_from + (equalize ? 0.8 : 1.0) * span;

  if (options.method == SphereMethod::progressive) {
    result.progressive = progressive_sphere_map(X0, result.F, options.progressive, control, options.stage,
                                                options.progress_from, map_end);
    result.S = std::move(result.progressive.S);
    result.progressive.S.resize(0, 3);
  } else {
    conformal_map(X0, options, control, result);
  }
  result.map_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  SphericalMapCheck check = check_spherical_map(result.S, result.F);
  if (check.bijective()) {
    result.map_area_distortion = area_distortion(X0, result.S, result.F);
    if (equalize) {
      checkpoint(control, options.stage, map_end);
      const auto equalize_start = std::chrono::steady_clock::now();
      result.equalization = equalize_area(result.S, result.F, face_areas(X0, result.F), options.equalization, control);
      result.equalize_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - equalize_start).count();
      check = check_spherical_map(result.S, result.F);  // bijective by construction; proven again
    }
  }
  result.flipped_faces = check.flipped_faces;
  result.degree = check.degree;
  if (!check.bijective())
    throw SphereParamError("the spherical parameterization is not bijective: " + std::to_string(check.flipped_faces) +
                           " flipped triangles remain (e.g. face " +
                           (check.flipped.empty() ? std::string("-") : std::to_string(check.flipped.front())) +
                           "), degree " + std::to_string(check.degree));
  result.area_distortion = area_distortion(X0, result.S, result.F);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace meshmark
