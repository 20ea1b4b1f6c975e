#include "client/terminal_progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace meshmark::cli {

TerminalProgress::TerminalProgress(std::string what, bool enabled, int threads)
    : what_(std::move(what)), active_(enabled && isatty(STDERR_FILENO) == 1) {
  control_.threads = threads;
  if (!active_) return;
  control_.report = [this](const std::string& stage, double progress) {
    std::fprintf(stderr, "\r\033[K%s: %s %3.0f %%", what_.c_str(), stage.c_str(), std::floor(100 * progress));
    std::fflush(stderr);
  };
}

TerminalProgress::~TerminalProgress() {
  if (active_) std::fprintf(stderr, "\r\033[K");
}

}  // namespace meshmark::cli
