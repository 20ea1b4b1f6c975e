#include "client/commands/stage_seconds.hpp"

namespace meshmark::cli {

namespace {
// Initialized with the other globals, before main runs.
const std::chrono::steady_clock::time_point process_start = std::chrono::steady_clock::now();
}  // namespace

double process_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - process_start).count();
}

}  // namespace meshmark::cli
