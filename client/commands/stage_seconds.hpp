#pragma once
// Wall time by stage, so that a command's `seconds` report adds up to what its user waited for.

#include <chrono>
#include <map>
#include <string>
#include <utility>

namespace meshmark::cli {

using StageSeconds = std::map<std::string, double>;

/// Seconds since this process started (before main).
double process_seconds();

/// Runs `work` and adds its wall time to seconds[stage]; returns what `work` returns.
template <typename Work>
auto timed(StageSeconds& seconds, const std::string& stage, Work&& work) {
  const auto start = std::chrono::steady_clock::now();
  auto result = std::forward<Work>(work)();
  seconds[stage] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace meshmark::cli
