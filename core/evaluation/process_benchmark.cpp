#include "core/evaluation/process_benchmark.hpp"

#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "core/evaluation/host_load.hpp"
#include "core/util/stopwatch.hpp"

namespace meshmark {

std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

namespace {

std::string tail_of(const std::filesystem::path& log, std::size_t bytes) {
  std::ifstream in(log, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.size() > bytes ? "…" + text.substr(text.size() - bytes) : text;
}

// The child: output to the log, then the shell.
[[noreturn]] void exec_shell(const std::string& shell_text, int log_fd) {
  if (::dup2(log_fd, STDOUT_FILENO) < 0 || ::dup2(log_fd, STDERR_FILENO) < 0) ::_exit(127);
  ::close(log_fd);
  ::execl("/bin/sh", "sh", "-c", shell_text.c_str(), static_cast<char*>(nullptr));
  ::_exit(127);
}

struct Round {
  std::vector<double> seconds, peak_mib;  // per command, the floor first
};

// One round on one mesh: every command once, starting at `first` and wrapping around.
Round run_round(const std::vector<TimedCommand>& commands, std::size_t first, const std::filesystem::path& mesh,
                const std::filesystem::path& work) {
  Round round{std::vector<double>(commands.size()), std::vector<double>(commands.size())};
  for (std::size_t k = 0; k < commands.size(); ++k) {
    const std::size_t i = (first + k) % commands.size();
    const auto out = work / ("out" + mesh.extension().string());
    const ProcessRun run = run_timed_process(substitute_paths(
        commands[i].command,
        {{"mesh", mesh.string()}, {"work", work.string()}, {"ext", mesh.extension().string()}, {"out", out.string()}}));
    std::filesystem::remove(out);
    round.seconds[i] = run.seconds;
    round.peak_mib[i] = run.peak_mib;
  }
  return round;
}

MeshProcessFigures summarize(const std::string& mesh, const std::vector<TimedCommand>& commands,
                             const std::vector<Round>& rounds) {
  MeshProcessFigures figures{mesh, {}, 0};
  for (std::size_t i = 0; i < commands.size(); ++i) {
    CommandFigures c{commands[i].name, {}, 0, 0, 0};
    std::vector<double> peaks, ratios;
    for (const Round& r : rounds) {
      c.seconds.push_back(r.seconds[i]);
      peaks.push_back(r.peak_mib[i]);
      ratios.push_back(r.seconds[0] > 0 ? r.seconds[i] / r.seconds[0] : 0.0);
    }
    c.median_seconds = median(c.seconds);
    c.median_peak_mib = median(peaks);
    c.median_floor_ratio = median(ratios);
    figures.commands.push_back(std::move(c));
  }
  return figures;
}

}  // namespace

const CommandFigures* MeshProcessFigures::find(const std::string& name) const {
  for (const CommandFigures& c : commands)
    if (c.name == name) return &c;
  return nullptr;
}

std::string substitute_paths(std::string text, const std::vector<std::pair<std::string, std::string>>& values) {
  // One pass from left to right: a value that holds a placeholder's text is not substituted again.
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const auto named_here = [&](const std::pair<std::string, std::string>& v) {
      return text[at] == '{' && text.compare(at + 1, v.first.size() + 1, v.first + "}") == 0;
    };
    const auto found = std::find_if(values.begin(), values.end(), named_here);
    if (found == values.end()) {
      out += text[at++];
      continue;
    }
    out += shell_quoted(found->second);
    at += found->first.size() + 2;
  }
  return out;
}

ProcessRun run_timed_process(const std::string& shell_text) {
  std::string log = (std::filesystem::temp_directory_path() / "meshmark-bench-log-XXXXXX").string();
  const int log_fd = ::mkstemp(log.data());  // a fresh file of ours: nobody else's name to follow
  if (log_fd < 0) throw std::runtime_error("benchmark: cannot create a log file in " + log);
  std::fflush(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(log_fd);
    std::filesystem::remove(log);
    throw std::runtime_error("benchmark: cannot fork");
  }
  if (pid == 0) exec_shell(shell_text, log_fd);
  ::close(log_fd);
  int status = 0;
  rusage usage{};
  pid_t waited;
  while ((waited = ::wait4(pid, &status, 0, &usage)) < 0 && errno == EINTR) {
  }
  const ProcessRun run{seconds_since(start), static_cast<double>(usage.ru_maxrss) / 1024.0};  // ru_maxrss: KiB
  const std::string output = waited == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0 ? "" : tail_of(log, 2000);
  std::filesystem::remove(log);
  if (waited != pid) throw std::runtime_error("benchmark: lost track of `" + shell_text + "`");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(
        "benchmark: `" + shell_text + "` failed (" +
        (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status)) : std::string("killed by a signal")) +
        "): " + output);
  return run;
}

std::vector<MeshProcessFigures> run_process_benchmark(const ProcessBenchmarkOptions& options) {
  std::vector<TimedCommand> commands = {options.floor};
  commands.insert(commands.end(), options.commands.begin(), options.commands.end());
  std::vector<MeshProcessFigures> figures;
  for (const auto& mesh : options.meshes) {
    std::string folder = (std::filesystem::temp_directory_path() / "meshmark-bench-XXXXXX").string();
    if (!::mkdtemp(folder.data())) throw std::runtime_error("benchmark: cannot create a folder in " + folder);
    const std::filesystem::path work = folder;
    try {
      for (const std::string& setup : options.setup)
        run_timed_process(substitute_paths(
            setup, {{"mesh", mesh.string()}, {"work", work.string()}, {"ext", mesh.extension().string()}}));
      std::vector<Round> rounds;
      const CpuJiffies before = cpu_jiffies();
      for (int r = 0; r < options.runs; ++r) {
        if (options.progress)
          options.progress(mesh.filename().string() + ": round " + std::to_string(r + 1) + " of " +
                           std::to_string(options.runs));
        rounds.push_back(run_round(commands, static_cast<std::size_t>(r) % commands.size(), mesh, work));
      }
      figures.push_back(summarize(mesh.filename().string(), commands, rounds));
      figures.back().steal_fraction = steal_fraction(before, cpu_jiffies());
    } catch (...) {
      std::filesystem::remove_all(work);
      throw;
    }
    std::filesystem::remove_all(work);
  }
  return figures;
}

}  // namespace meshmark
