#pragma once
// The options of how a local computation runs, shared by sphere, embed, detect and trace:
// progress on the terminal, and the threads its parallel loops use.

#include <CLI/CLI.hpp>

namespace meshmark::cli {

struct RunArgs {
  bool quiet = false;  ///< no progress on standard error
  int threads = 0;     ///< --threads, else MESHMARK_THREADS; 0: the hardware's, at most 8

  void add_to(CLI::App* cmd);
};

/// --threads (env MESHMARK_THREADS, 0..64) into `threads`: for commands that show no progress.
void add_threads_option(CLI::App* cmd, int& threads);

}  // namespace meshmark::cli
