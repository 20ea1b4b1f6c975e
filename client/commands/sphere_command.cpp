// meshmark sphere MESH [--out FILE] [--json]: the bijective spherical parameterization.

#include <cstdio>
#include <iostream>
#include <optional>

#include "client/commands/commands.hpp"
#include "client/commands/run_options_cli.hpp"
#include "client/terminal_progress.hpp"
#include "core/io/document_surface.hpp"
#include "core/io/write_mesh.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "core/param/sphere_param.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

namespace {

struct SphereArgs {
  std::string mesh, out;
  bool json = false;
  RunArgs run;
  std::string method = "progressive";
  std::optional<bool> area_correction;
  SphereParamOptions options;
};

void add_tuning_options(CLI::App* cmd, SphereParamOptions& options) {
  cmd->add_option("--settle-steps", options.progressive.settle_steps,
                  "Progressive map: descent steps of each re-inserted vertex alone")
      ->capture_default_str();
  cmd->add_option("--coarse-sweeps", options.progressive.coarse_sweeps,
                  "Progressive map: stretch-descent passes per level up to 1000 vertices")
      ->capture_default_str();
  cmd->add_option("--level-sweeps", options.progressive.level_sweeps, "Progressive map: passes per larger level")
      ->capture_default_str();
  cmd->add_option("--final-sweeps", options.progressive.final_sweeps, "Progressive map: passes on the whole mesh")
      ->capture_default_str();
  cmd->add_option("--time-step", options.flow.time_step, "Conformal flow: time step (unit area)")
      ->capture_default_str();
  cmd->add_option("--max-iterations", options.flow.max_iterations, "Conformal flow: steps at most")
      ->capture_default_str();
  cmd->add_option("--roundness", options.flow.roundness_tolerance,
                  "Conformal flow: stop at this relative RMS radial deviation")
      ->capture_default_str();
}

void print_sphere_text(const std::string& file, const Mesh& mesh, const SphereParam& param) {
  const AreaDistortion& c = param.map_area_distortion;
  const AreaDistortion& d = param.area_distortion;
  std::printf(
      "%s: %lld vertices, %s map\n  flipped faces %zu\n  degree        %.12f\n"
      "  area ratio    p05 %.3g  median %.3g  p95 %.3g  (before area correction: p05 %.3g  median %.3g  p95 %.3g)\n"
      "  seconds       %.3f (map %.3f, area correction %.3f in %d steps)\n",
      file.c_str(), static_cast<long long>(mesh.V.rows()), to_string(param.method).c_str(), param.flipped_faces,
      param.degree, d.p05, d.median, d.p95, c.p05, c.median, c.p95, param.seconds, param.map_seconds,
      param.equalize_seconds, param.equalization.steps);
}

int run_sphere(const SphereArgs& args) {
  const Mesh mesh = read_surface(args.mesh);
  const MeshReport report = validate_mesh(mesh);
  if (!report.closed_genus_zero) {
    const auto& why = report.problems.empty() ? report.sphere_problems : report.problems;
    std::fprintf(stderr, "meshmark: %s cannot be parameterized: %s\n", args.mesh.c_str(),
                 why.empty() ? "it is not one closed genus-0 surface" : why.front().c_str());
    return kExitRefused;
  }
  std::optional<TerminalProgress> progress(std::in_place, "sphere", !args.run.quiet, args.run.threads);
  const SphereParam param = sphere_param(mesh, args.options, progress->control());
  progress.reset();
  if (!args.out.empty()) write_mesh(args.out, Mesh{param.S, mesh.F}, {.lossless_text = true});
  if (args.json) {
    nlohmann::json j = param;
    j["file"] = args.mesh;
    j["vertices"] = mesh.V.rows();
    std::cout << j.dump(2) << "\n";
  } else {
    print_sphere_text(args.mesh, mesh, param);
  }
  return kExitOk;
}

}  // namespace

void register_sphere(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("sphere", "Map a genus-0 mesh bijectively onto the unit sphere");
  auto args = std::make_shared<SphereArgs>();
  cmd->add_option("mesh", args->mesh, "Mesh file (.obj, .off, .ply, .stl, .glb, .gltf, .3mf)")->required();
  cmd->add_option("--out", args->out, "Write the spherical mesh (original connectivity) here");
  cmd->add_flag("--json", args->json, "Print JSON");
  args->run.add_to(cmd);
  cmd->add_option("--method", args->method, "progressive (bijective by construction) or conformal-flow")
      ->capture_default_str();
  cmd->add_flag("--area-correction,!--no-area-correction", args->area_correction,
                "Run (or skip) the area-correcting flow after the map (default: only after the conformal flow)");
  add_tuning_options(cmd, args->options);
  cmd->callback([&action, args] {
    args->options.method = parse_sphere_method(args->method);
    args->options.equalize_area = args->area_correction;
    action = [args] { return run_sphere(*args); };
  });
}

}  // namespace meshmark::cli
