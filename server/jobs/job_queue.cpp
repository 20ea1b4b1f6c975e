#include "server/jobs/job_queue.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace meshmark::server {

JobQueue::JobQueue(std::size_t capacity, int workers, Runner runner, Options options)
    : capacity_(capacity), runner_(std::move(runner)), options_(options) {
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

bool JobQueue::reserve() {
  std::lock_guard lock(mutex_);
  if (stopping_ || queue_.size() + reserved_ >= capacity_) return false;
  ++reserved_;
  return true;
}

void JobQueue::release_reservation() {
  std::lock_guard lock(mutex_);
  if (reserved_ > 0) --reserved_;
}

void JobQueue::push(const std::string& job_id) {
  {
    std::lock_guard lock(mutex_);
    if (reserved_ > 0) --reserved_;
    queue_.push_back(job_id);
  }
  wake_.notify_one();
}

void JobQueue::push_recovered(const std::string& job_id) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(job_id);
  }
  wake_.notify_one();
}

JobQueue::Cancel JobQueue::cancel(const std::string& job_id) {
  std::lock_guard lock(mutex_);
  const auto it = std::find(queue_.begin(), queue_.end(), job_id);
  if (it != queue_.end()) {
    queue_.erase(it);
    return Cancel::dequeued;
  }
  const auto running = running_.find(job_id);
  if (running != running_.end()) {
    running->second->store(true);
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

std::string JobQueue::next_job(std::unique_lock<std::mutex>& lock) {
  while (!stopping_) {
    const auto now = Clock::now();
    auto due = retrying_.end();
    for (auto it = retrying_.begin(); it != retrying_.end(); ++it)
      if (it->second.due <= now && (due == retrying_.end() || it->second.due < due->second.due)) due = it;
    if (due != retrying_.end()) {
      std::string id = due->first;
      return id;  // stays in retrying_ (with its pause) until it runs through
    }
    if (!queue_.empty()) {
      std::string id = queue_.front();
      queue_.pop_front();
      return id;
    }
    if (retrying_.empty()) {
      wake_.wait(lock);
    } else {
      auto soonest = retrying_.begin()->second.due;
      for (const auto& [id, r] : retrying_) soonest = std::min(soonest, r.due);
      wake_.wait_until(lock, soonest);
    }
  }
  return {};
}

void JobQueue::work() {
  while (true) {
    std::string id;
    auto cancel = std::make_shared<std::atomic<bool>>(false);
    {
      std::unique_lock lock(mutex_);
      id = next_job(lock);
      if (id.empty()) return;
      running_[id] = cancel;
      if (auto r = retrying_.find(id); r != retrying_.end())
        r->second.due = Clock::time_point::max();  // not twice at once
    }
    bool retry = false;
    try {
      runner_(id, *cancel);  // the runner records every outcome it can in the store
    } catch (const RetryLater& e) {
      retry = true;
      spdlog::warn("job {}: {}; it runs again when the store accepts it", id, e.what());
    } catch (const std::exception& e) {
      // The store failed in a way retrying will not mend: the job stays as the store last saw it
      // and runs again after a restart; the daemon keeps serving.
      spdlog::error("job {}: {}", id, e.what());
    } catch (...) {
      spdlog::error("job {}: unknown error", id);
    }
    {
      std::lock_guard lock(mutex_);
      running_.erase(id);
      if (retry) {
        auto [it, fresh] = retrying_.try_emplace(id, Retry{Clock::now(), options_.first_retry});
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
