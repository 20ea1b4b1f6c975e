#include "server/jobs/job_queue.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace meshmark::server {

JobQueue::JobQueue(std::size_t capacity, int workers, Runner runner, const Options& options)
    : capacity_(capacity),
      runner_(std::move(runner)),
      options_(options),
      owner_places_(
          std::max<std::size_t>(1, static_cast<std::size_t>(options.owner_share * static_cast<double>(capacity)))) {
  for (int i = 0; i < workers; ++i) workers_.emplace_back([this] { work(); });
}

JobQueue::~JobQueue() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

bool JobQueue::reserve(const std::string& owner) {
  std::lock_guard lock(mutex_);
  if (stopping_ || queue_.size() + reserved_ >= capacity_) return false;
  if (!owner.empty() && held_[owner] >= owner_places_) return false;
  ++reserved_;
  if (!owner.empty()) ++held_[owner];
  return true;
}

void JobQueue::release_place(const std::string& owner) {
  if (owner.empty()) return;
  if (auto it = held_.find(owner); it != held_.end() && --it->second == 0) held_.erase(it);
}

void JobQueue::release_reservation(const std::string& owner) {
  std::lock_guard lock(mutex_);
  if (reserved_ > 0) --reserved_;
  release_place(owner);
}

void JobQueue::push(const QueuedJob& job) {
  bool busy = false;
  {
    std::lock_guard lock(mutex_);
    if (reserved_ > 0) --reserved_;
    queue_.push_back(job);  // its owner's place moves from reserved to queued
    busy = more_jobs_than_workers();
  }
  wake_.notify_all();
  if (busy) announce();
}

void JobQueue::push_recovered(const QueuedJob& job) {
  bool busy = false;
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(job);
    if (!job.owner.empty()) ++held_[job.owner];
    busy = more_jobs_than_workers();
  }
  wake_.notify_all();
  if (busy) announce();
}

bool JobQueue::more_jobs_than_workers() const { return queue_.size() + running_.size() > workers_.size(); }

void JobQueue::announce() const {
  if (!options_.announce) return;
  try {
    options_.announce();
  } catch (const std::exception& e) {  // the others still find the job when they next poll
    spdlog::debug("announcing a job others could run: {}", e.what());
  }
}

std::size_t JobQueue::held_by(const std::string& owner) const {
  std::lock_guard lock(mutex_);
  const auto it = held_.find(owner);
  return it == held_.end() ? 0 : it->second;
}

JobQueue::Cancel JobQueue::cancel(const std::string& job_id) {
  std::lock_guard lock(mutex_);
  const auto it = std::find_if(queue_.begin(), queue_.end(), [&](const Queued& q) { return q.job_id == job_id; });
  if (it != queue_.end()) {
    release_place(it->owner);
    queue_.erase(it);
    return Cancel::dequeued;
  }
  const auto running = running_.find(job_id);
  if (running != running_.end()) {
    running->second.cancel->store(true);
    return Cancel::signaled;
  }
  const auto retry = retrying_.find(job_id);
  if (retry != retrying_.end()) {
    retry->second.due = Clock::now();
    wake_.notify_all();
    return Cancel::retried_now;
  }
  return Cancel::unknown;
}

JobQueue::Counts JobQueue::counts() const {
  std::lock_guard lock(mutex_);
  return {queue_.size(), running_.size(), retrying_.size()};
}

bool JobQueue::drain(std::chrono::seconds grace) {
  std::unique_lock lock(mutex_);
  stopping_ = true;
  wake_.notify_all();
  return idle_.wait_for(lock, grace, [this] { return running_.empty(); });
}

bool JobQueue::waits_for_preparation(std::deque<Queued>::const_iterator job) const {
  if (job->prepares || job->model_id.empty()) return false;
  const auto prepares_it = [&](const Queued& other) { return other.prepares && other.model_id == job->model_id; };
  if (std::any_of(queue_.cbegin(), job, prepares_it)) return true;
  for (const auto& [id, r] : running_)
    if (prepares_it(r.job)) return true;
  for (const auto& [id, r] : retrying_)
    if (prepares_it(r.job)) return true;
  return false;
}

std::deque<JobQueue::Queued>::iterator JobQueue::fairest_queued() {
  std::map<std::string, std::size_t> running_by_owner;
  for (const auto& [id, r] : running_) ++running_by_owner[r.job.owner];
  auto best = queue_.end();
  for (auto it = queue_.begin(); it != queue_.end(); ++it)
    if (!waits_for_preparation(it) &&
        (best == queue_.end() || running_by_owner[it->owner] < running_by_owner[best->owner]))
      best = it;
  return best;
}

JobQueue::Queued JobQueue::next_job(std::unique_lock<std::mutex>& lock) {
  while (!stopping_) {
    const auto now = Clock::now();
    auto due = retrying_.end();
    for (auto it = retrying_.begin(); it != retrying_.end(); ++it)
      if (it->second.due <= now && (due == retrying_.end() || it->second.due < due->second.due)) due = it;
    if (due != retrying_.end()) return due->second.job;  // stays in retrying_ until it runs through
    if (const auto fairest = fairest_queued(); fairest != queue_.end()) {
      Queued next = *fairest;
      release_place(fairest->owner);
      queue_.erase(fairest);
      return next;
    }
    if (auto job = claimed(lock)) return *job;
    if (stopping_) break;
    const auto wake = next_wake();
    if (wake == Clock::time_point::max()) wake_.wait(lock);
    else wake_.wait_until(lock, wake);
  }
  return {};
}

std::optional<JobQueue::Queued> JobQueue::claimed(std::unique_lock<std::mutex>& lock) {
  if (!options_.claim || Clock::now() < next_claim_) return std::nullopt;
  next_claim_ = Clock::now() + options_.claim_interval;  // the other idle workers wait for this answer
  lock.unlock();
  std::optional<Queued> job;
  try {
    job = options_.claim();
  } catch (const std::exception& e) {
    spdlog::warn("claiming queued work: {}", e.what());
  }
  lock.lock();
  if (stopping_) return std::nullopt;   // draining: its lease runs out and another daemon runs it
  if (job) next_claim_ = Clock::now();  // there may be more
  return job;
}

JobQueue::Clock::time_point JobQueue::next_wake() const {
  auto soonest = options_.claim ? next_claim_ : Clock::time_point::max();
  for (const auto& [id, r] : retrying_) soonest = std::min(soonest, r.due);
  return soonest;
}

void JobQueue::wake_idle() {
  {
    std::lock_guard lock(mutex_);
    next_claim_ = Clock::now();
  }
  wake_.notify_all();
}

void JobQueue::work() {
  while (true) {
    std::string id;
    auto cancel = std::make_shared<std::atomic<bool>>(false);
    {
      std::unique_lock lock(mutex_);
      const Queued next = next_job(lock);
      if (next.job_id.empty()) return;
      id = next.job_id;
      running_[id] = {cancel, next};
      if (auto r = retrying_.find(id); r != retrying_.end())
        r->second.due = Clock::time_point::max();  // not twice at once
    }
    bool retry = false;
    try {
      runner_(id, *cancel);  // the runner records every outcome it can in the store
    } catch (const RetryLater& e) {
      retry = true;
      spdlog::warn("job {}: {}; it runs again later", id, e.what());
    } catch (const std::exception& e) {
      // The store failed in a way retrying will not mend: the job stays as the store last saw it
      // and runs again after a restart; the daemon keeps serving.
      spdlog::error("job {}: {}", id, e.what());
    } catch (...) {
      spdlog::error("job {}: unknown error", id);
    }
    {
      std::lock_guard lock(mutex_);
      const Queued job = running_[id].job;
      running_.erase(id);
      if (retry) {
        auto [it, fresh] = retrying_.try_emplace(id, Retry{Clock::now(), options_.first_retry, job});
        if (!fresh) it->second.pause = std::min(options_.max_retry, it->second.pause * 2);
        it->second.due = Clock::now() + it->second.pause;
      } else {
        retrying_.erase(id);
      }
    }
    wake_.notify_all();
    idle_.notify_all();
  }
}

}  // namespace meshmark::server
