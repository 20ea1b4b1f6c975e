#pragma once
// A bounded queue of job ids and the compute workers that run them: separate threads from the
// HTTP ones, so a burst of uploads never starves the workers nor the other way round.
//
// A job whose outcome the store could not take (the disk is full) is not dropped: it waits in
// the queue's retry list, with growing pauses, and runs again until its result is stored. It is
// counted, can be canceled, and never sits 'running' or 'queued' in the store without a worker
// that owns it.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace meshmark::server {

/// Thrown by a runner when the store cannot take a job's outcome yet (full disk): the queue
/// runs the job again later.
class RetryLater : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class JobQueue {
 public:
  using Runner = std::function<void(const std::string& job_id, const std::atomic<bool>& cancel)>;

  struct Options {
    std::chrono::milliseconds first_retry{1000};  ///< pause before the first retry of a job the store refused
    std::chrono::milliseconds max_retry{30'000};  ///< the pause doubles up to this
  };

  JobQueue(std::size_t capacity, int workers, Runner runner)
      : JobQueue(capacity, workers, std::move(runner), Options{}) {}
  JobQueue(std::size_t capacity, int workers, Runner runner, Options options);
  ~JobQueue();
  JobQueue(const JobQueue&) = delete;
  JobQueue& operator=(const JobQueue&) = delete;

  /// Holds a place in the queue (false when full or draining); the place is used by push().
  bool reserve();
  void release_reservation();
  /// Queues a job for which a place was reserved.
  void push(const std::string& job_id);
  /// Queues a job found at start-up, whatever the capacity.
  void push_recovered(const std::string& job_id);

  enum class Cancel { dequeued, signaled, retried_now, unknown };
  /// A queued job is dropped; a running one is signaled; one waiting to retry runs now (and finds
  /// its cancel request in the store).
  Cancel cancel(const std::string& job_id);

  struct Counts {
    std::size_t queued = 0, running = 0, retrying = 0;
  };
  Counts counts() const;
  std::size_t depth() const { return counts().queued; }
  std::size_t running() const { return counts().running; }
  std::size_t capacity() const { return capacity_; }

  /// Stops handing out jobs and waits up to `grace` for the running ones; true if they finished.
  /// Jobs still queued or waiting to retry stay so in the store and run after the next start.
  bool drain(std::chrono::seconds grace);

 private:
  using Clock = std::chrono::steady_clock;
  struct Retry {
    Clock::time_point due;
    std::chrono::milliseconds pause;
  };

  void work();
  // The next job to run (a due retry first), or empty when stopping. Called with the lock held.
  std::string next_job(std::unique_lock<std::mutex>& lock);

  const std::size_t capacity_;
  Runner runner_;
  Options options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<std::string> queue_;
  std::map<std::string, Retry> retrying_;
  std::size_t reserved_ = 0;
  std::map<std::string, std::shared_ptr<std::atomic<bool>>> running_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace meshmark::server
