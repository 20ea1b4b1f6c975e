#pragma once
// Whole processes timed side by side: our own commands and anyone else's (a peer's service, an
// older build of ours), run in turn on the same meshes. The order rotates every round, so a slow
// spell of the host does not fall on the same command every time, and each time is also given as a multiple of
// the floor, a command that only reads and writes the same mesh, timed in the same round: a ratio
// that survives a noisy host where seconds do not.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace meshmark {

/// Shell text with placeholders, each replaced by a quoted path: {mesh} the input, {work} the
/// mesh's scratch folder (kept through its rounds), {ext} the mesh's extension (as `{work}/copy{ext}`),
/// {out} a fresh file in {work} with the mesh's extension (removed after each run).
struct TimedCommand {
  std::string name;  ///< the row; another tool's command named like one of ours is compared to it
  std::string command;
};

struct ProcessBenchmarkOptions {
  std::vector<std::filesystem::path> meshes;
  TimedCommand floor;              ///< read and write the mesh: the unit of the ratios
  std::vector<std::string> setup;  ///< run once per mesh before its rounds, untimed (e.g. a marked copy)
  std::vector<TimedCommand> commands;
  int runs = 5;
  std::function<void(const std::string&)> progress;
};

struct CommandFigures {
  std::string name;
  std::vector<double> seconds;  ///< per round
  double median_seconds = 0;
  double median_peak_mib = 0;     ///< the process's (and its children's) peak resident memory
  double median_floor_ratio = 0;  ///< median over rounds of its time ÷ the floor's in that round
};

struct MeshProcessFigures {
  std::string mesh;
  std::vector<CommandFigures> commands;  ///< the floor first, then in the options' order
  double steal_fraction = 0;             ///< CPU steal during this mesh's rounds
  const CommandFigures* find(const std::string& name) const;
};

/// One run of `shell_text` under /bin/sh: its wall time and peak resident memory (wait4's, which
/// covers the children it waited for). Throws std::runtime_error, with the end of what it printed,
/// if it does not exit with status 0.
struct ProcessRun {
  double seconds = 0;
  double peak_mib = 0;
};
ProcessRun run_timed_process(const std::string& shell_text);

/// `text` as one single-quoted shell word.
std::string shell_quoted(const std::string& text);

/// `text` with every {name} in `values` replaced by the value, single-quoted for the shell; a
/// value is never searched for placeholders itself.
std::string substitute_paths(std::string text, const std::vector<std::pair<std::string, std::string>>& values);

/// Runs every command `runs` times per mesh, the floor among them. Throws std::runtime_error when
/// a command fails.
std::vector<MeshProcessFigures> run_process_benchmark(const ProcessBenchmarkOptions& options);

}  // namespace meshmark
