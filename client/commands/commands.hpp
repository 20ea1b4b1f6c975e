#pragma once
// Each subcommand of `meshmark` registers itself on the app and returns its exit status
// through a callback run after parsing.

#include <CLI/CLI.hpp>
#include <functional>

namespace meshmark::cli {

/// Filled in by the subcommand that was chosen; returns the process exit status.
using Action = std::function<int()>;

void register_info(CLI::App& app, Action& action);
void register_sphere(CLI::App& app, Action& action);
void register_attack(CLI::App& app, Action& action);
void register_embed(CLI::App& app, Action& action);
void register_detect(CLI::App& app, Action& action);
void register_compare(CLI::App& app, Action& action);
void register_eval(CLI::App& app, Action& action);
void register_remote(CLI::App& app, Action& action);
void register_bench(CLI::App& app, Action& action);

/// Exit statuses shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRefused = 1;  ///< ran, and the answer is "no" (e.g. mesh not valid)
inline constexpr int kExitError = 2;    ///< could not run (bad arguments, unreadable file)

}  // namespace meshmark::cli
