#include "core/param/sphere_param.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/mesh/orientation.hpp"
#include "core/param/check_spherical_map.hpp"
#include "core/param/massmatrix.hpp"
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

SphereParam sphere_param(const Mesh& mesh, const SphereParamOptions& options, const JobControl* control) {
  const auto start = std::chrono::steady_clock::now();
  SphereParam result;
  result.F = orient_outward(mesh.V, mesh.F);
  result.flipped_input = result.F(0, 1) != mesh.F(0, 1);
  const Vertices X0 = apply(unit_area_normalization(mesh.V, result.F), mesh.V);

  const ConformalFlowResult flow = conformal_flow(X0, result.F, options.flow, control);
  result.flow_iterations = flow.iterations;
  result.factorizations = flow.factorizations;
  result.flow_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  result.S = project_to_sphere(flow.X);
  mobius_center(result.S, vertex_areas(X0, result.F), options.centering);

  SphericalMapCheck check = check_spherical_map(result.S, result.F);
  result.flipped_before_repair = check.flipped_faces;
  if (check.flipped_faces > 0) {
    const RepairResult repair = repair_spherical_flips(result.S, result.F, options.repair);
    result.repair_rounds = repair.rounds;
    check = check_spherical_map(result.S, result.F);
  }
  if (check.bijective()) {
    result.conformal_area_distortion = area_distortion(X0, result.S, result.F);
    if (options.equalize_area) {
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
                           " flipped triangles remain after repair (e.g. face " +
                           (check.flipped.empty() ? std::string("-") : std::to_string(check.flipped.front())) +
                           "), degree " + std::to_string(check.degree));
  result.area_distortion = area_distortion(X0, result.S, result.F);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace meshmark
