#pragma once
// Progress, cancellation and time limits for long computations, checked between stages. The
// core never blocks on it; a caller (the daemon's workers) passes one in and the pipeline calls
// checkpoint() as it goes.

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace meshmark {

class Canceled : public std::runtime_error {
 public:
  Canceled() : std::runtime_error("canceled") {}
};

class TimeLimitExceeded : public std::runtime_error {
 public:
  TimeLimitExceeded() : std::runtime_error("the job's time limit was exceeded") {}
};

struct JobControl {
  /// Called at every checkpoint with the stage starting and the overall fraction done (0..1).
  std::function<void(const std::string& stage, double progress)> report;
  const std::atomic<bool>* cancel = nullptr;
  std::optional<std::chrono::steady_clock::time_point> deadline;

  /// Reports, then throws Canceled or TimeLimitExceeded if asked to stop.
  void checkpoint(const std::string& stage, double progress) const {
    if (report) report(stage, progress);
    if (cancel && cancel->load()) throw Canceled();
    if (deadline && std::chrono::steady_clock::now() > *deadline) throw TimeLimitExceeded();
  }
};

/// checkpoint() on a control that may be absent.
inline void checkpoint(const JobControl* control, const std::string& stage, double progress) {
  if (control) control->checkpoint(stage, progress);
}

}  // namespace meshmark
