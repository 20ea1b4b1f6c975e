#pragma once
// Seconds elapsed on the steady clock, for the stage timings every step reports.

#include <chrono>

namespace meshmark {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace meshmark
