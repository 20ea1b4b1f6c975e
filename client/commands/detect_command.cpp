// meshmark detect SUSPECT --original ORIG --key KEY [--bits N] [--expect HEX] [scheme options] [--json]

#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "client/commands/commands.hpp"
#include "client/terminal_progress.hpp"
#include "client/commands/watermark_options_cli.hpp"
#include "core/io/document_surface.hpp"
#include "core/watermark/watermark.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

namespace {

// One line a non-expert can act on: what was found, and how likely that is by coincidence.
std::string plain_verdict(const DetectResult& r) {
  char chance[64];
  std::snprintf(chance, sizeof chance, "1e%.0f", std::floor(r.log10_p_value));
  if (r.detected)
    return "marked with this key" + (r.payload ? ", payload " + hex_from_bits(*r.payload) : std::string()) +
           "; chance of coincidence below " + chance;
  return "no watermark of this key found (the strongest evidence would occur by chance with probability " +
         (r.log10_p_value > -3 ? std::to_string(r.p_value).substr(0, 5) : std::string(chance)) + ")";
}

}  // namespace


void register_detect(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("detect", "Detect and read a payload in a suspect mesh, against its original");
  struct Args {
    std::string suspect, original, key, expect;
    int bits = 64;
    SchemeArgs scheme;
    bool json = false;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("suspect", args->suspect, "Suspect mesh (any triangle mesh: open, in pieces, any genus)")->required();
  cmd->add_option("--original", args->original, "The original (unmarked) mesh")->required();
  cmd->add_option("--key", args->key, "The owner's secret key")->required();
  cmd->add_option("--bits", args->bits, "Payload length in bits")->capture_default_str();
  cmd->add_option("--expect", args->expect, "Expected payload (hex): reports the bit error rate");
  args->scheme.add_to(cmd);
  cmd->add_flag("--json", args->json, "Print JSON");
  cmd->add_flag("--quiet", args->quiet, "No progress on standard error (shown only when it is a terminal)");
  cmd->callback([&action, args] {
    action = [args] {
      DetectOptions options;
      options.watermark = args->scheme.watermark();
      options.payload_bits = args->bits;
      if (!args->expect.empty()) {
        options.expected = bits_from_hex(args->expect);
        if (args->bits == 64 && static_cast<int>(options.expected->size()) != 64)
          options.payload_bits = static_cast<int>(options.expected->size());
      }
      PrepareOptions prepare;
      prepare.base = args->scheme.base_solid();
      std::optional<TerminalProgress> progress(std::in_place, "detect", !args->quiet);
      const PreparedModel model = prepare_model(read_surface(args->original), prepare, progress->control());
      const Mesh suspect = read_welded_scene(args->suspect);
      const DetectResult result = detect_watermark(model, suspect, args->key, options, nullptr, progress->control());
      progress.reset();
      if (args->json) {
        nlohmann::json j = result;
        j["suspect"] = args->suspect;
        j["original"] = args->original;
        std::cout << j.dump(2) << "\n";
      } else {
        std::printf("%s: %s\n", args->suspect.c_str(), plain_verdict(result).c_str());
        std::printf("  evidence: %s; blind decode %s%s%s; correlation %.3f\n  alignment rms %.2e, scale %.6f\n",
                    result.evidence.c_str(), hex_from_bits(result.decoded).c_str(),
                    result.checksum_ok ? " (checksum matches)" : " (checksum fails)",
                    result.ber ? (", bit error rate " + std::to_string(*result.ber)).c_str() : "", result.correlation,
                    result.alignment.rms, result.alignment.transform.scale);
      }
      return kExitOk;
    };
  });
}

}  // namespace meshmark::cli
