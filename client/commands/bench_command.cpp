// meshmark bench [--meshes ...] [--runs N] [--subdivide N] [--json]
// Times every pipeline stage and its peak memory (median of N runs, each in a fresh process),
// fits how time and memory grow with the mesh size, and checks the performance targets.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "client/commands/bench_processes.hpp"
#include "client/commands/commands.hpp"
#include "client/commands/run_options_cli.hpp"
#include "core/evaluation/benchmark.hpp"
#include "core/util/huge_pages.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark::cli {

namespace {

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

struct Target {
  std::size_t mesh;   // index in the figures
  std::string stage;  // a stage, or "peak" for the peak memory
  double limit;       // seconds or MiB
  std::string text;
};

// The targets, for the default meshes only: the first is the bunny, the last (when `large`) the
// bunny subdivided twice.
std::vector<Target> targets(std::size_t meshes, bool large, bool default_meshes) {
  if (!default_meshes) return {};
  std::vector<Target> t = {{0, "total.cold_embed", 2.0, "bunny cold embed <= 2 s"},
                           {0, "parameterize", 1.0, "bunny parameterization <= 1 s"},
                           {0, "total.warm_embed", 0.3, "bunny warm embed <= 0.3 s"},
                           {0, "total.detect", 1.0, "bunny detection <= 1 s"}};
  if (large && meshes >= 2) {
    t.push_back({meshes - 1, "total.cold_embed", 40.0, "557k cold embed <= 40 s"});
    t.push_back({meshes - 1, "parameterize", 20.0, "557k parameterization <= 20 s"});
    t.push_back({meshes - 1, "total.detect", 15.0, "557k detection <= 15 s"});
    t.push_back({meshes - 1, "peak", 2048.0, "557k peak memory <= 2 GiB"});
  }
  return t;
}

double value_of(const MeshFigures& m, const std::string& stage) {
  if (stage == "peak") return m.peak_mib;
  const StageFigures* s = m.find(stage);
  return s ? s->median_seconds : 0.0;
}

// Exponent of stage time (or peak memory) against vertex count over all meshes.
double exponent(const std::vector<MeshFigures>& figures, const std::string& stage) {
  std::vector<double> x, y;
  for (const MeshFigures& m : figures) {
    if (stage != "peak" && !m.find(stage)) continue;  // a stage the mesh's basis has not (bumps, or the sphere's)
    x.push_back(static_cast<double>(m.vertices));
    y.push_back(value_of(m, stage));
  }
  return growth_exponent(x, y);
}

nlohmann::json to_json(const std::vector<MeshFigures>& figures, int runs, int threads, bool large,
                       bool default_meshes) {
  nlohmann::json j = {
      {"machine",
       {{"cpu", cpu_model()}, {"cores", std::thread::hardware_concurrency()}, {"memory", huge_page_setting()}}},
      {"runs", runs},
      {"threads", resolve_threads(threads)}};
  for (const MeshFigures& m : figures) {
    nlohmann::json mesh = {{"mesh", m.mesh},
                           {"vertices", m.vertices},
                           {"faces", m.faces},
                           {"peak_mib", m.peak_mib},
                           {"cpu_steal", m.steal_fraction}};
    for (const StageFigures& s : m.stages)
      mesh["stages"].push_back({{"stage", s.stage},
                                {"median_seconds", s.median_seconds},
                                {"seconds", s.seconds},
                                {"peak_mib", s.median_peak_mib},
                                {"floor_ratio", s.median_floor_ratio}});
    j["meshes"].push_back(mesh);
  }
  for (const char* stage : {"total.cold_embed", "total.warm_embed", "total.detect", "peak"})
    j["growth_exponents"][stage] = exponent(figures, stage);
  for (const Target& t : targets(figures.size(), large, default_meshes))
    j["targets"].push_back({{"target", t.text},
                            {"value", value_of(figures[t.mesh], t.stage)},
                            {"met", value_of(figures[t.mesh], t.stage) <= t.limit}});
  return j;
}

void print_markdown(const std::vector<MeshFigures>& figures, int runs, int threads, bool large, bool default_meshes) {
  std::printf(
      "Machine: %u cores, %s; %d threads. Median of %d runs, each in a fresh process; peak = resident memory.\n\n",
      std::thread::hardware_concurrency(), cpu_model().c_str(), resolve_threads(threads), runs);
  std::printf(
      "Each stage also as a multiple of the same run's load + write (× floor), which a busy host changes "
      "less than seconds.\n\n| stage |");
  for (const MeshFigures& m : figures) std::printf(" %s (%lld V) s | × floor | MiB |", m.mesh.c_str(), m.vertices);
  std::printf(" time exponent |\n|---|");
  for (std::size_t i = 0; i < figures.size(); ++i) std::printf("---|---|---|");
  std::printf("---|\n");
  for (const auto& [stage, what] : benchmark_stages()) {
    std::printf("| %s |", stage.c_str());
    for (const MeshFigures& m : figures) {
      const StageFigures* s = m.find(stage);
      if (s) std::printf(" %.3f | %.1f | %.0f |", s->median_seconds, s->median_floor_ratio, s->median_peak_mib);
      else std::printf(" – | – | – |");
    }
    const std::string& stage_name = stage;  // clang 14 cannot capture a structured binding
    const auto having = std::count_if(figures.begin(), figures.end(),
                                      [&](const MeshFigures& m) { return m.find(stage_name) != nullptr; });
    if (having > 1) std::printf(" %.2f |\n", exponent(figures, stage));
    else std::printf(" – |\n");
  }
  std::printf("\nCPU steal (time the hypervisor took) during the runs:");
  for (const MeshFigures& m : figures) std::printf(" %s %.0f%%", m.mesh.c_str(), 100 * m.steal_fraction);
  std::printf("\nMemory: %s\n", huge_page_setting().c_str());
  if (figures.size() > 1) std::printf("Peak memory grows as V^%.2f.\n", exponent(figures, "peak"));
  if (!targets(figures.size(), large, default_meshes).empty()) std::printf("\nTargets:\n");
  for (const Target& t : targets(figures.size(), large, default_meshes)) {
    const double v = value_of(figures[t.mesh], t.stage);
    std::printf("- %s: %.3g %s\n", t.text.c_str(), v, v <= t.limit ? "(met)" : "(MISSED)");
  }
}

}  // namespace

void register_bench(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("bench", "Time and peak memory of every pipeline stage, and the performance targets");
  struct Args {
    std::vector<std::string> meshes;
    int runs = 3, subdivide = 2, threads = 0;
    bool json = false, processes = false;
    std::vector<std::string> versus;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--meshes", args->meshes,
                  "Meshes (default: bunny.obj and armadillo.obj in $MESHMARK_SHARED/meshes, else ../shared/meshes)");
  cmd->add_option("--runs", args->runs, "Runs per mesh (medians are reported)")
      ->capture_default_str()
      ->check(CLI::Range(1, 50));
  cmd->add_option("--subdivide", args->subdivide, "Also the first mesh Loop-subdivided this many times (0: not)")
      ->capture_default_str()
      ->check(CLI::Range(0, 3));
  add_threads_option(cmd, args->threads);
  cmd->add_flag("--json", args->json, "Print JSON instead of Markdown");
  cmd->add_flag("--processes", args->processes,
                "Whole processes instead of stages: our cold and warm embed and detections as a user runs them, "
                "alternating, each also as a multiple of reading and writing the mesh (attack reorder)");
  cmd->add_option("--versus", args->versus,
                  "NAME=COMMAND: also time another command side by side (implies --processes); shell text with "
                  "{mesh} (the input) and {out} (a file to write); NAME like one of ours (e.g. \"cold embed\") "
                  "compares the two");
  cmd->callback([&action, args] {
    action = [args] {
      BenchmarkOptions options;
      const bool default_meshes = args->meshes.empty();
      if (default_meshes) args->meshes = shared_meshes({"bunny.obj", "armadillo.obj"});
      if (args->processes || !args->versus.empty())
        return run_process_bench(
            {args->meshes, default_meshes, args->subdivide, args->runs, args->threads, args->versus, args->json});
      for (const auto& m : args->meshes) options.meshes.emplace_back(m);
      options.runs = args->runs;
      options.threads = args->threads;
      options.subdivided_steps = args->subdivide;
      options.progress = [](const std::string& what) { std::fprintf(stderr, "bench: %s\n", what.c_str()); };
      const auto figures = run_benchmark(options);
      const bool large = args->subdivide > 0;
      if (args->json) std::cout << to_json(figures, args->runs, args->threads, large, default_meshes).dump(2) << "\n";
      else print_markdown(figures, args->runs, args->threads, large, default_meshes);
      return kExitOk;
    };
  });
}

}  // namespace meshmark::cli
