#pragma once
// A bounded queue of job ids and the compute workers that run them: separate threads from the
// HTTP ones, so a burst of uploads never starves the workers nor the other way round.
//
// Owners share it: one owner holds at most its share of the places, and a free worker takes the
// oldest job of an owner with the fewest jobs running, so one owner's burst cannot lock others out.
//
// A job that uses a model waits while a job preparing that model is queued before it, running or
// waiting to retry: it becomes runnable when its model is (and then finds the model ready, or
// failed).
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
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace meshmark::server {

/// Thrown by a runner when a job cannot run or end yet (a full or unreachable store, a model
/// another daemon still prepares): the queue runs the job again later.
class RetryLater : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One job as the queue knows it.
struct QueuedJob {
  std::string job_id;
  std::string owner;     ///< for the owner's share and fair order (empty: none)
  std::string model_id;  ///< the model it prepares or uses (empty: none)
  bool prepares = false;
};

class JobQueue {
 public:
  using Runner = std::function<void(const std::string& job_id, const std::atomic<bool>& cancel)>;

  struct Options {
    std::chrono::milliseconds first_retry{1000};  ///< pause before the first retry of a job the store refused
    std::chrono::milliseconds max_retry{30'000};  ///< the pause doubles up to this
    double owner_share = 0.5;                     ///< the share of the places one owner may hold (at least one place)
    /// Where an idle worker finds work when nothing here can run (another daemon's queued jobs
    /// on a shared store, Store::claim_queued_job); none: only what is pushed. Asked at most once
    /// per claim_interval while it finds nothing, and at once after wake_idle().
    std::function<std::optional<QueuedJob>()> claim;
    std::chrono::milliseconds claim_interval{1000};
    /// Called (without the lock) when a job is pushed while every worker here is taken: idle
    /// daemons elsewhere may claim it now (Store::announce_claimable_jobs). Its errors are logged.
    std::function<void()> announce;
  };

  JobQueue(std::size_t capacity, int workers, Runner runner)
      : JobQueue(capacity, workers, std::move(runner), Options{}) {}
  JobQueue(std::size_t capacity, int workers, Runner runner, const Options& options);
  ~JobQueue();
  JobQueue(const JobQueue&) = delete;
  JobQueue& operator=(const JobQueue&) = delete;

  /// Holds a place in the queue for `owner` (false when full, draining, or when the owner already
  /// holds owner_places()); the place is used by push().
  bool reserve(const std::string& owner = {});
  void release_reservation(const std::string& owner = {});
  /// Queues a job for which a place was reserved by the same owner.
  void push(const QueuedJob& job);
  void push(const std::string& job_id, const std::string& owner = {}) { push(QueuedJob{job_id, owner, {}, false}); }
  /// Queues a job found at start-up, whatever the capacity.
  void push_recovered(const QueuedJob& job);
  /// There may be work to claim elsewhere (a notification from the store): idle workers ask now.
  void wake_idle();

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
  /// The places one owner may hold, and how many `owner` holds (reserved or queued).
  std::size_t owner_places() const { return owner_places_; }
  std::size_t held_by(const std::string& owner) const;

  /// Stops handing out jobs and waits up to `grace` for the running ones; true if they finished.
  /// Jobs still queued or waiting to retry stay so in the store and run after the next start.
  bool drain(std::chrono::seconds grace);

 private:
  using Clock = std::chrono::steady_clock;
  using Queued = QueuedJob;
  struct Retry {
    Clock::time_point due;
    std::chrono::milliseconds pause;
    Queued job;
  };

  void work();
  // The next job to run (a due retry first, then a queued one, then one claimed elsewhere), or
  // none (an empty id) when stopping. Called with the lock held.
  Queued next_job(std::unique_lock<std::mutex>& lock);
  // A job options_.claim found, asked without the lock; none when it is not time to ask.
  std::optional<Queued> claimed(std::unique_lock<std::mutex>& lock);
  Clock::time_point next_wake() const;  // with the lock held: the soonest retry or claim

  struct Running {
    std::shared_ptr<std::atomic<bool>> cancel;
    Queued job;
  };
  // With the lock held:
  void release_place(const std::string& owner);
  bool more_jobs_than_workers() const;
  void announce() const;  // without the lock
  // The oldest runnable queued job among the owners with the fewest jobs running; end() if none.
  std::deque<Queued>::iterator fairest_queued();
  bool waits_for_preparation(std::deque<Queued>::const_iterator job) const;

  const std::size_t capacity_;
  Runner runner_;
  Options options_;
  const std::size_t owner_places_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<Queued> queue_;
  std::map<std::string, Retry> retrying_;
  std::size_t reserved_ = 0;
  std::map<std::string, std::size_t> held_;  // owner → places reserved or queued
  std::map<std::string, Running> running_;
  bool stopping_ = false;
  Clock::time_point next_claim_{};
  std::vector<std::thread> workers_;
};

}  // namespace meshmark::server
