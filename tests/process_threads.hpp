#pragma once
// How many threads this process runs, and the most it ran at once while some work went on:
// for tests that a computation uses exactly the threads its caller gave it.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <filesystem>
#include <thread>

namespace meshmark::test {

inline std::size_t threads_in_process() {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

/// The most threads this process had at once while `work` ran beyond those it had when the call
/// began (the test's own, a sanitizer runtime's), the watching thread included. It looks as often
/// as the scheduler lets it (sleeping between looks missed a job's every worker thread once, under
/// ThreadSanitizer on two busy cores), so only a thread that lives less than a look may be missed.
template <typename Work>
std::size_t new_threads_while(const Work& work) {
  // ThreadSanitizer's runtime starts a thread of its own with the first thread a process makes.
  std::thread([] {}).join();
  const std::size_t before = threads_in_process();
  std::atomic<bool> done{false};
  std::atomic<std::size_t> peak{0};
  std::thread watcher([&] {
    while (!done.load()) {
      peak = std::max(peak.load(), threads_in_process());
      std::this_thread::yield();
    }
  });
  work();
  done = true;
  watcher.join();
  return peak.load() - before;
}

}  // namespace meshmark::test
