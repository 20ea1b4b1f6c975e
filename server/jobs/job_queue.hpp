#pragma once
// A bounded queue of job ids and the compute workers that run them: separate threads from the
// HTTP ones, so a burst of uploads never starves the workers nor the other way round.

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

class JobQueue {
 public:
  using Runner = std::function<void(const std::string& job_id, const std::atomic<bool>& cancel)>;

  JobQueue(std::size_t capacity, int workers, Runner runner);
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

  enum class Cancel { dequeued, signaled, unknown };
  Cancel cancel(const std::string& job_id);

  std::size_t depth() const;
  std::size_t running() const;
  std::size_t capacity() const { return capacity_; }

  /// Stops handing out jobs and waits up to `grace` for the running ones; true if they finished.
  /// Jobs still queued stay queued in the store and run after the next start.
  bool drain(std::chrono::seconds grace);

 private:
  void work();

  const std::size_t capacity_;
  Runner runner_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<std::string> queue_;
  std::size_t reserved_ = 0;
  std::map<std::string, std::shared_ptr<std::atomic<bool>>> running_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace meshmark::server
