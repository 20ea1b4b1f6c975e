#include "client/commands/bench_processes.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "client/commands/commands.hpp"
#include "core/evaluation/benchmark.hpp"
#include "core/evaluation/host_load.hpp"
#include "core/evaluation/process_benchmark.hpp"
#include "core/util/huge_pages.hpp"

namespace meshmark::cli {

namespace {

constexpr const char* kFloor = "read + write (attack reorder)";
constexpr const char* kTheirs = " (theirs)";

// Our rows: the commands a user runs, the way the README shows them. {work}/copy{ext} is the
// copy handed out, its record beside it; the suspect is that copy moved.
ProcessBenchmarkOptions our_commands(int threads) {
  const std::string self = shell_quoted(std::filesystem::read_symlink("/proc/self/exe").string());
  const std::string common =
      " --key 'bench key' --quiet" + (threads > 0 ? " --threads " + std::to_string(threads) : "");
  const std::string embed = self + " embed {mesh} {out} --payload 0123456789abcdef" + common;
  const std::string suspect = " {work}/suspect{ext}";
  ProcessBenchmarkOptions options;
  options.floor = {kFloor, self + " attack reorder {mesh} {out}"};
  options.setup = {self + " embed {mesh} {work}/copy{ext} --payload fedcba9876543210 --record {work}/copy.record" +
                       " --cache {work}/cache" + common,
                   self + " attack similarity {work}/copy{ext}" + suspect};
  options.commands = {
      {"cold embed", embed + " --no-cache --no-record"},
      {"warm embed", embed + " --cache {work}/cache --no-record"},
      {"detect --record", self + " detect" + suspect + " --record {work}/copy.record" + common},
      {"detect --original", self + " detect" + suspect + " --original {mesh} --cache {work}/cache" + common},
  };
  return options;
}

std::vector<TimedCommand> parse_versus(const std::vector<std::string>& versus) {
  std::vector<TimedCommand> commands;
  for (const std::string& v : versus) {
    const auto equals = v.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == v.size())
      throw std::invalid_argument("--versus wants NAME=COMMAND, got: " + v);
    commands.push_back({v.substr(0, equals) + kTheirs, v.substr(equals + 1)});
  }
  return commands;
}

// Median over rounds of ours ÷ theirs, for a command of theirs named after one of ours.
double median_ratio(const CommandFigures& ours, const CommandFigures& theirs) {
  std::vector<double> ratios;
  for (std::size_t r = 0; r < ours.seconds.size() && r < theirs.seconds.size(); ++r)
    if (theirs.seconds[r] > 0) ratios.push_back(ours.seconds[r] / theirs.seconds[r]);
  return median(ratios);
}

const CommandFigures* ours_for(const MeshProcessFigures& mesh, const CommandFigures& theirs) {
  const auto at = theirs.name.rfind(kTheirs);
  return at == std::string::npos ? nullptr : mesh.find(theirs.name.substr(0, at));
}

struct ProcessTarget {
  std::size_t mesh;
  std::string command;  // or "peak" (the largest of our commands' peaks)
  double limit;         // seconds or MiB
  std::string text;
};

// Issue 26's whole-process targets, for the default meshes: the bunny first, the subdivided last.
std::vector<ProcessTarget> process_targets(std::size_t meshes, bool large) {
  std::vector<ProcessTarget> t = {{0, "cold embed", 0.9, "bunny cold embed <= 0.9 s"},
                                  {0, "detect --record", 0.35, "bunny detect --record <= 0.35 s"}};
  if (large) {
    t.push_back({meshes - 1, "cold embed", 12.0, "557k cold embed <= 12 s"});
    t.push_back({meshes - 1, "detect --record", 3.0, "557k detect --record <= 3 s"});
    t.push_back({meshes - 1, "peak", 1024.0, "557k peak memory <= 1 GiB"});
  }
  return t;
}

double target_value(const MeshProcessFigures& mesh, const std::string& command) {
  if (command != "peak") return mesh.find(command)->median_seconds;
  double peak = 0;
  for (const CommandFigures& c : mesh.commands)
    if (c.name.find(kTheirs) == std::string::npos) peak = std::max(peak, c.median_peak_mib);
  return peak;
}

nlohmann::json to_json(const std::vector<MeshProcessFigures>& figures, const std::vector<ProcessTarget>& targets) {
  nlohmann::json j = {{"floor", kFloor}, {"memory", huge_page_setting()}};
  for (const MeshProcessFigures& m : figures) {
    nlohmann::json mesh = {{"mesh", m.mesh}, {"cpu_steal", m.steal_fraction}};
    for (const CommandFigures& c : m.commands) {
      nlohmann::json row = {{"command", c.name},
                            {"median_seconds", c.median_seconds},
                            {"seconds", c.seconds},
                            {"peak_mib", c.median_peak_mib},
                            {"floor_ratio", c.median_floor_ratio}};
      if (const CommandFigures* ours = ours_for(m, c)) row["ours_over_theirs"] = median_ratio(*ours, c);
      mesh["commands"].push_back(row);
    }
    j["meshes"].push_back(mesh);
  }
  for (const ProcessTarget& t : targets) {
    const double v = target_value(figures[t.mesh], t.command);
    j["targets"].push_back({{"target", t.text}, {"value", v}, {"met", v <= t.limit}});
  }
  return j;
}

void print_markdown(const std::vector<MeshProcessFigures>& figures, const std::vector<ProcessTarget>& targets,
                    int runs) {
  std::printf(
      "Whole processes, %d rounds alternating, medians: seconds, × the floor (%s, the same round), peak MiB.\n\n", runs,
      kFloor);
  std::printf("| command |");
  for (const MeshProcessFigures& m : figures) std::printf(" %s s | × floor | MiB |", m.mesh.c_str());
  std::printf("\n|---|");
  for (std::size_t i = 0; i < figures.size(); ++i) std::printf("---|---|---|");
  std::printf("\n");
  for (std::size_t row = 0; row < figures.front().commands.size(); ++row) {
    std::printf("| %s |", figures.front().commands[row].name.c_str());
    for (const MeshProcessFigures& m : figures)
      std::printf(" %.3f | %.1f | %.0f |", m.commands[row].median_seconds, m.commands[row].median_floor_ratio,
                  m.commands[row].median_peak_mib);
    std::printf("\n");
  }
  for (const MeshProcessFigures& m : figures)
    for (const CommandFigures& c : m.commands)
      if (const CommandFigures* ours = ours_for(m, c))
        std::printf("\n%s, %s: ours ÷ theirs %.2f (median of the rounds' ratios)", m.mesh.c_str(), ours->name.c_str(),
                    median_ratio(*ours, c));
  std::printf("\n\nCPU steal during the rounds:");
  for (const MeshProcessFigures& m : figures) std::printf(" %s %.0f%%", m.mesh.c_str(), 100 * m.steal_fraction);
  std::printf("\nMemory: %s\n", huge_page_setting().c_str());
  if (!targets.empty()) std::printf("\nTargets (whole processes):\n");
  for (const ProcessTarget& t : targets) {
    const double v = target_value(figures[t.mesh], t.command);
    std::printf("- %s: %.3g %s\n", t.text.c_str(), v, v <= t.limit ? "(met)" : "(MISSED)");
  }
}

}  // namespace

int run_process_bench(const ProcessBenchArguments& arguments) {
  ProcessBenchmarkOptions options = our_commands(arguments.threads);
  const auto theirs = parse_versus(arguments.versus);
  options.commands.insert(options.commands.end(), theirs.begin(), theirs.end());
  for (const auto& m : arguments.meshes) options.meshes.emplace_back(m);
  options.runs = arguments.runs;
  options.progress = [](const std::string& what) { std::fprintf(stderr, "bench: %s\n", what.c_str()); };
  const auto generated = std::filesystem::temp_directory_path() / ("meshmark-bench-" + std::to_string(::getpid()));
  std::vector<MeshProcessFigures> figures;
  try {
    if (arguments.subdivide > 0 && !options.meshes.empty()) {
      const std::filesystem::path first = options.meshes.front();  // a copy: the push below moves the vector
      options.progress("generating " + first.filename().string() + ", Loop-subdivided");
      std::filesystem::create_directories(generated);
      options.meshes.push_back(generated /
                               (first.stem().string() + "-loop" + std::to_string(arguments.subdivide) + ".ply"));
      write_subdivided(first, arguments.subdivide, options.meshes.back());
    }
    figures = run_process_benchmark(options);
  } catch (...) {
    std::filesystem::remove_all(generated);
    throw;
  }
  std::filesystem::remove_all(generated);
  const auto targets = arguments.default_meshes ? process_targets(figures.size(), arguments.subdivide > 0)
                                                : std::vector<ProcessTarget>{};
  if (arguments.json) std::cout << to_json(figures, targets).dump(2) << "\n";
  else print_markdown(figures, targets, arguments.runs);
  return kExitOk;
}

}  // namespace meshmark::cli
