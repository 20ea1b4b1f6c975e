#include "client/commands/run_options_cli.hpp"

namespace meshmark::cli {

void add_threads_option(CLI::App* cmd, int& threads) {
  cmd->add_option("--threads", threads,
                  "Threads for the parallel steps (0: the hardware's, at most 8); the result is the same on any count")
      ->envname("MESHMARK_THREADS")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
}

void RunArgs::add_to(CLI::App* cmd) {
  cmd->add_flag("--quiet", quiet, "No progress on standard error (shown only when it is a terminal)");
  add_threads_option(cmd, threads);
}

}  // namespace meshmark::cli
