#pragma once
// Each subcommand of `meshmark` registers itself on the app and returns its exit status
// through a callback run after parsing.

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

namespace meshmark::cli {

/// Filled in by the subcommand that was chosen; returns the process exit status.
using Action = std::function<int()>;

void register_info(CLI::App& app, Action& action);
void register_example(CLI::App& app, Action& action);
void register_sphere(CLI::App& app, Action& action);
void register_attack(CLI::App& app, Action& action);
void register_embed(CLI::App& app, Action& action);
void register_detect(CLI::App& app, Action& action);
void register_compare(CLI::App& app, Action& action);
void register_eval(CLI::App& app, Action& action);
void register_remote(CLI::App& app, Action& action);
void register_bench(CLI::App& app, Action& action);
void register_trace(CLI::App& app, Action& action);

/// The shared test meshes named, in $MESHMARK_SHARED/meshes or else ../shared/meshes: the
/// defaults of `eval` and `bench`.
inline std::vector<std::string> shared_meshes(std::initializer_list<const char*> names) {
  const char* env = std::getenv("MESHMARK_SHARED");
  const std::string dir = std::string(env ? env : "../shared") + "/meshes";
  std::vector<std::string> paths;
  for (const char* name : names) paths.push_back(dir + "/" + name);
  return paths;
}

/// Exit statuses shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRefused = 1;  ///< ran, and the answer is "no" (e.g. mesh not valid)
inline constexpr int kExitError = 2;    ///< could not run (bad arguments, unreadable file)

}  // namespace meshmark::cli
