// meshmark sphere MESH [--out FILE] [--json]: the bijective spherical parameterization.

#include <cstdio>
#include <iostream>

#include "client/commands/commands.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "core/param/sphere_param.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

void register_sphere(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("sphere", "Map a genus-0 mesh bijectively onto the unit sphere");
  struct Args {
    std::string mesh, out;
    bool json = false;
    SphereParamOptions options;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("mesh", args->mesh, "Mesh file (.obj, .off, .ply, .stl)")->required();
  cmd->add_option("--out", args->out, "Write the spherical mesh (original connectivity) here");
  cmd->add_flag("--json", args->json, "Print JSON");
  cmd->add_flag("!--conformal", args->options.equalize_area, "Skip the area-correcting step (conformal map only)");
  cmd->add_option("--time-step", args->options.flow.time_step, "Flow time step (unit area)")->capture_default_str();
  cmd->add_option("--max-iterations", args->options.flow.max_iterations, "Flow steps at most")->capture_default_str();
  cmd->add_option("--roundness", args->options.flow.roundness_tolerance, "Stop the flow at this relative RMS radial deviation")
      ->capture_default_str();
  cmd->callback([&action, args] {
    action = [args] {
      const Mesh mesh = read_mesh(args->mesh).mesh;
      const MeshReport report = validate_mesh(mesh);
      if (!report.valid) {
        std::fprintf(stderr, "meshmark: %s cannot be parameterized: %s\n", args->mesh.c_str(),
                     report.problems.front().c_str());
        return kExitRefused;
      }
      const SphereParam param = sphere_param(mesh, args->options);
      if (!args->out.empty()) write_mesh(args->out, Mesh{param.S, mesh.F});
      if (args->json) {
        nlohmann::json j = param;
        j["file"] = args->mesh;
        j["vertices"] = mesh.V.rows();
        std::cout << j.dump(2) << "\n";
      } else {
        const AreaDistortion& c = param.conformal_area_distortion;
        const AreaDistortion& d = param.area_distortion;
        std::printf("%s: %lld vertices\n  flipped faces %zu (before repair %zu)\n  degree        %.12f\n"
                    "  iterations    %d flow steps, %d area-correcting steps\n"
                    "  area ratio    p05 %.3g  median %.3g  p95 %.3g  (conformal map: p05 %.3g  median %.3g  p95 %.3g)\n"
                    "  seconds       %.3f (flow %.3f, area correction %.3f)\n",
                    args->mesh.c_str(), static_cast<long long>(mesh.V.rows()), param.flipped_faces,
                    param.flipped_before_repair, param.degree, param.flow_iterations, param.equalization.steps,
                    d.p05, d.median, d.p95, c.p05, c.median, c.p95, param.seconds, param.flow_seconds,
                    param.equalize_seconds);
      }
      return kExitOk;
    };
  });
}

}  // namespace meshmark::cli
