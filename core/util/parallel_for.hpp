#pragma once
// Splits [0, n) into one contiguous block per thread and runs `body(begin, end)` on each.
// For loops whose iterations write only their own outputs: the result is then the same, bit
// for bit, whatever the thread count. Small ranges run on the calling thread. The thread count
// is always the caller's (a JobControl carries it down a pipeline): there is no process-wide
// setting, so a daemon's concurrent jobs and an evaluation's parallel trials each use theirs.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <exception>
#include <thread>
#include <vector>

namespace meshmark {

/// The hardware's threads, at most 8 (beyond that the memory-bound loops here gain nothing).
int hardware_threads();

/// `requested` when positive; 0 (or less) means hardware_threads().
int resolve_threads(int requested);

/// Runs body over [0, n) on up to `threads` threads (0: hardware_threads()), each block at
/// least `min_per_thread` long.
template <typename Body>
void parallel_for(std::int64_t n, int threads_requested, const Body& body, std::int64_t min_per_thread = 2048) {
  const int threads = static_cast<int>(
      std::min<std::int64_t>(resolve_threads(threads_requested), n / std::max<std::int64_t>(1, min_per_thread)));
  if (threads <= 1) {
    if (n > 0) body(std::int64_t{0}, n);
    return;
  }
  const std::int64_t chunk = (n + threads - 1) / threads;
  std::vector<std::thread> pool;
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
  for (int t = 1; t < threads; ++t)
    pool.emplace_back([&, t] {
      try {
        body(t * chunk, std::min(n, (t + 1) * chunk));
      } catch (...) {
        errors[static_cast<std::size_t>(t)] = std::current_exception();
      }
    });
  try {
    body(std::int64_t{0}, std::min(n, chunk));
  } catch (...) {
    errors[0] = std::current_exception();
  }
  for (auto& thread : pool) thread.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

/// Runs `body(i)` for every i in [0, n) on `threads` threads (at least one), each taking the next
/// index as soon as it is free: for iterations of very unequal cost (whole evaluation trials).
/// After an exception no new index is started; the first one is rethrown once all threads stop.
template <typename Body>
void parallel_for_each(std::int64_t n, int threads, const Body& body) {
  std::atomic<std::int64_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    for (std::int64_t i; !failed.load() && (i = next++) < n;) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(worker);
  worker();
  for (auto& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace meshmark
