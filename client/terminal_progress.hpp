#pragma once
// Progress of a long local command on standard error: "embed: parameterize 42 %", rewritten in
// place, only when standard error is a terminal and the user did not ask for --quiet (scripts
// and pipes see nothing). The line is cleared when the progress ends. Its control also carries
// the threads the command may use.

#include <memory>
#include <string>

#include "core/util/job_control.hpp"

namespace meshmark::cli {

class TerminalProgress {
 public:
  /// Shows progress for `what` when `enabled` and standard error is a terminal; the computation
  /// runs on `threads` threads (0: the hardware's).
  TerminalProgress(std::string what, bool enabled, int threads);
  ~TerminalProgress();  ///< clears the line
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  /// The control to pass to the core: it reports only when progress is shown.
  const JobControl* control() const { return &control_; }

 private:
  std::string what_;
  bool active_ = false;
  JobControl control_;
};

}  // namespace meshmark::cli
