// meshmark compare A B [--json]: MRMS and Hausdorff distances, relative to A's bbox diagonal.

#include <cstdio>
#include <iostream>

#include "client/commands/commands.hpp"
#include "core/io/document_surface.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

void register_compare(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("compare", "Distortion between two meshes: MRMS and Hausdorff distance");
  struct Args {
    std::string a, b;
    bool json = false;
    CompareOptions options;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("a", args->a, "Reference mesh (its bounding-box diagonal is the unit)")->required();
  cmd->add_option("b", args->b, "Other mesh")->required();
  cmd->add_option("--samples", args->options.samples, "Points sampled on each surface")->capture_default_str();
  cmd->add_flag("--json", args->json, "Print JSON");
  cmd->callback([&action, args] {
    action = [args] {
      const SurfaceDistance d = compare_meshes(read_surface(args->a), read_surface(args->b), args->options);
      if (args->json) {
        nlohmann::json j = d;
        j["a"] = args->a;
        j["b"] = args->b;
        std::cout << j.dump(2) << "\n";
      } else {
        std::printf("MRMS %.6f %%  Hausdorff %.6f %%  (of the bounding-box diagonal of %s, %.6g)\n",
                    100 * d.mrms_relative(), 100 * d.hausdorff_relative(), args->a.c_str(), d.diagonal);
      }
      return kExitOk;
    };
  });
}

}  // namespace meshmark::cli
