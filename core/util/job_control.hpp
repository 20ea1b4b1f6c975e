#pragma once
// How a long computation runs: its progress, cancellation, time limit and threads. The core
// never blocks on it; a caller (the daemon's workers, the CLI) passes one in, the pipeline calls
// checkpoint() between stages and poll() inside long ones (solver iterations, registration
// rounds, parsing), so that a cancel or a time limit takes effect within a fraction of a second,
// and its parallel loops use threads_of() threads.

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/util/parallel_for.hpp"

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
  /// Threads the computation's parallel loops may use; 0: the hardware's, at most 8.
  int threads = 0;

  /// Reports, then throws Canceled or TimeLimitExceeded if asked to stop.
  void checkpoint(const std::string& stage, double progress) const {
    if (report) report(stage, progress);
    poll();
  }

  /// Throws Canceled or TimeLimitExceeded if asked to stop; reports nothing. Cheap (an atomic
  /// load and a clock read): call it every few thousand iterations of an inner loop.
  void poll() const {
    if (cancel && cancel->load()) throw Canceled();
    if (deadline && std::chrono::steady_clock::now() > *deadline) throw TimeLimitExceeded();
  }
};

/// A control for one part of a computation whose own checkpoints run over [from, to]: it reports
/// them as the parent's progress over [into_from, into_to], so that repeated parts (a reading
/// per candidate registration) keep the overall progress growing. Same cancel, deadline, threads.
inline JobControl rescaled(const JobControl& parent, double from, double to, double into_from, double into_to) {
  JobControl part = parent;
  if (parent.report)
    part.report = [report = parent.report, from, to, into_from, into_to](const std::string& stage, double progress) {
      report(stage, into_from + (progress - from) / (to - from) * (into_to - into_from));
    };
  return part;
}

/// poll() on a control that may be absent.
inline void poll(const JobControl* control) {
  if (control) control->poll();
}

/// The threads a computation under `control` may use: its setting, or without a control (or with
/// 0) the hardware's, at most 8.
inline int threads_of(const JobControl* control) { return resolve_threads(control ? control->threads : 0); }

/// checkpoint() on a control that may be absent.
inline void checkpoint(const JobControl* control, const std::string& stage, double progress) {
  if (control) control->checkpoint(stage, progress);
}

/// Progress through one long stage, reported as overall progress from `from` to `to`: whenever 1 %
/// of the stage has passed since the last report, when a second has, and at its end, so a job's
/// progress moves smoothly (callers update at least every 1 % of their work).
class ProgressMeter {
 public:
  ProgressMeter(const JobControl* control, std::string stage, double from, double to)
      : control_(control), stage_(std::move(stage)), from_(from), to_(to) {}
  /// `fraction` of the stage done (0..1); polls the control every time.
  void update(double fraction) {
    if (!control_) return;
    const auto now = std::chrono::steady_clock::now();
    if (fraction >= reported_ + 0.01 || now - last_ >= std::chrono::seconds(1) || (fraction >= 1 && reported_ < 1)) {
      reported_ = fraction;
      last_ = now;
      control_->checkpoint(stage_, from_ + (to_ - from_) * std::min(1.0, std::max(0.0, fraction)));
    } else {
      control_->poll();
    }
  }

 private:
  const JobControl* control_;
  std::string stage_;
  double from_, to_;
  double reported_ = -1;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

/// Consecutive stages of one computation: each start() is a checkpoint and ends the previous
/// stage, whose wall time goes into `seconds[stage]`; finish() ends the last.
class StageTimer {
 public:
  StageTimer(std::map<std::string, double>& seconds, const JobControl* control)
      : seconds_(seconds), control_(control) {}
  void start(const std::string& stage, double progress) {
    finish();
    checkpoint(control_, stage, progress);
    stage_ = stage;
    start_ = std::chrono::steady_clock::now();
  }
  void finish() {
    if (stage_.empty()) return;
    seconds_[stage_] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    stage_.clear();
  }

 private:
  std::map<std::string, double>& seconds_;
  const JobControl* control_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace meshmark
