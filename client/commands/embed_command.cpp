// meshmark embed IN OUT --key KEY --payload HEX [scheme options] [--json]

#include <chrono>
#include <cstdio>
#include <iostream>

#include "client/commands/commands.hpp"
#include "client/commands/watermark_options_cli.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "core/watermark/watermark.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

void register_embed(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("embed", "Embed a keyed payload in a mesh");
  struct Args {
    std::string in, out, key, payload;
    SchemeArgs scheme;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("in", args->in, "Original mesh")->required();
  cmd->add_option("out", args->out, "Watermarked mesh (format from the extension)")->required();
  cmd->add_option("--key", args->key, "The owner's secret key")->required();
  cmd->add_option("--payload", args->payload, "Payload as hex digits (4 bits each), e.g. 0123456789abcdef")->required();
  args->scheme.add_to(cmd);
  cmd->add_flag("--json", args->json, "Print JSON");
  cmd->callback([&action, args] {
    action = [args] {
      using Clock = std::chrono::steady_clock;
      auto t0 = Clock::now();
      const Mesh mesh = read_mesh(args->in).mesh;
      const double load = std::chrono::duration<double>(Clock::now() - t0).count();
      const Bits payload = bits_from_hex(args->payload);
      PrepareOptions prepare;
      prepare.base = args->scheme.base_solid();
      const PreparedModel model = prepare_model(mesh, prepare);
      const WatermarkOptions options = args->scheme.watermark();
      const EmbedResult result = embed_watermark(model, args->key, payload, options);
      t0 = Clock::now();
      write_mesh(args->out, result.mesh);
      const double write = std::chrono::duration<double>(Clock::now() - t0).count();
      const SurfaceDistance distortion = compare_meshes(mesh, result.mesh);
      if (args->json) {
        nlohmann::json j = embed_report(model, options, result, distortion);
        j["input"] = args->in;
        j["output"] = args->out;
        j["payload"] = hex_from_bits(payload);
        j["seconds"]["load"] = load;
        j["seconds"]["write"] = write;
        std::cout << j.dump(2) << "\n";
      } else {
        std::printf("%s -> %s: %d-bit payload in %d carriers on grid level %d (%d samples); "
                    "distortion MRMS %.4f%%, Hausdorff %.4f%% of the bbox diagonal\n",
                    args->in.c_str(), args->out.c_str(), static_cast<int>(payload.size()), result.carriers,
                    model.level(), model.sample_count(), 100 * distortion.mrms_relative(),
                    100 * distortion.hausdorff_relative());
      }
      return kExitOk;
    };
  });
}

}  // namespace meshmark::cli
