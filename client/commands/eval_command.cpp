// meshmark eval [--meshes ...] [--trials N] [--quick] [--tables T ...] [--strength P] [--threads N] [--null N]
// [--json] [--out FILE]
// Exit status 0 when every promised figure holds, 1 when one is missed, 2 on errors.

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "client/commands/commands.hpp"
#include "client/commands/eval_report.hpp"
#include "core/util/atomic_file.hpp"

namespace meshmark::cli {

void register_eval(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("eval", "Robustness and imperceptibility evaluation over meshes, attacks and trials");
  struct Args {
    std::vector<std::string> meshes;
    int trials = 5, threads = 2, null_detections = 0;
    double strength = WatermarkOptions{}.strength_percent;
    bool quick = false, json = false;
    std::string out, basis = "auto";
    std::vector<std::string> tables;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--meshes", args->meshes,
                  "Meshes (default: the four valid shared meshes in $MESHMARK_SHARED/meshes, else ../shared/meshes)");
  cmd->add_option("--trials", args->trials, "Trials (random key and payload each)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  cmd->add_option("--threads", args->threads, "Worker threads")->capture_default_str()->check(CLI::Range(1, 64));
  cmd->add_flag("--quick", args->quick, "The CI subset: the promised rows, one trial, the default scheme");
  cmd->add_option("--tables", args->tables, "Only these tables of attacks (default: all)")
      ->check(CLI::IsMember({"paper", "benchmark", "beyond"}));
  cmd->add_option("--strength", args->strength,
                  "Strength of the marks, % of the diagonal; below the default the promise is the mild attacks")
      ->capture_default_str()
      ->check(CLI::Range(kMinStrengthPercent, kMaxStrengthPercent));
  cmd->add_flag("--json", args->json, "Print JSON instead of Markdown");
  cmd->add_option("--basis", args->basis, "auto (what each mesh takes) or bumps (every mesh on bumps, to compare)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "bumps"}));
  cmd->add_option("--out", args->out, "Also write the Markdown report to this file");
  cmd->add_option("--null", args->null_detections,
                  "Null detections per mesh (unmarked or wrong key): the measured false-alarm rate and p-value tail")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  cmd->callback([&action, args] {
    action = [args] {
      EvalOptions options;
      for (const auto& m : args->meshes.empty()
                               ? shared_meshes({"bunny.obj", "mannequin.off", "spot.obj", "armadillo.obj"})
                               : args->meshes)
        options.meshes.emplace_back(m);
      options.trials = args->trials;
      options.threads = args->threads;
      options.quick = args->quick;
      options.force_bumps = args->basis == "bumps";
      options.null_detections = args->null_detections;
      options.strength_percent = args->strength;
      options.tables = {args->tables.begin(), args->tables.end()};
      options.progress = [](const std::string& what) { std::fprintf(stderr, "eval: %s\n", what.c_str()); };
      const EvalResults results = evaluate(options);
      std::string command = "meshmark eval";
      if (args->quick) command += " --quick";
      else command += " --trials " + std::to_string(args->trials);
      if (!args->meshes.empty()) command += " --meshes ...";
      if (options.force_bumps) command += " --basis bumps";
      for (const auto& table : args->tables) command += " --tables " + table;
      if (options.null_detections > 0) command += " --null " + std::to_string(options.null_detections);
      if (args->strength != WatermarkOptions{}.strength_percent) {
        char text[32];
        std::snprintf(text, sizeof text, " --strength %g", args->strength);
        command += text;
      }
      const std::string markdown = eval_markdown(results, command);
      if (!args->out.empty()) write_file_atomically(args->out, markdown);
      std::cout << (args->json ? eval_json(results, command).dump(2) + "\n" : markdown);
      const auto missed = check_requirements(results);
      for (const auto& m : missed) std::fprintf(stderr, "eval: requirement missed: %s\n", m.c_str());
      return missed.empty() ? kExitOk : kExitRefused;
    };
  });
}

}  // namespace meshmark::cli
