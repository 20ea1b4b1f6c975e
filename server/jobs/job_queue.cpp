#include "server/jobs/job_queue.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace meshmark::server {

JobQueue::JobQueue(std::size_t capacity, int workers, Runner runner) : capacity_(capacity), runner_(std::move(runner)) {
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
  return Cancel::unknown;
}

std::size_t JobQueue::depth() const {
  std::lock_guard lock(mutex_);
  return queue_.size();
}

std::size_t JobQueue::running() const {
  std::lock_guard lock(mutex_);
  return running_.size();
}

bool JobQueue::drain(std::chrono::seconds grace) {
  std::unique_lock lock(mutex_);
  stopping_ = true;
  wake_.notify_all();
  return idle_.wait_for(lock, grace, [this] { return running_.empty(); });
}

void JobQueue::work() {
  while (true) {
    std::string id;
    auto cancel = std::make_shared<std::atomic<bool>>(false);
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      id = queue_.front();
      queue_.pop_front();
      running_[id] = cancel;
    }
    try {
      runner_(id, *cancel);  // the runner records every outcome it can in the store
    } catch (const std::exception& e) {
      // The store itself failed (disk full, I/O error): the job stays as the store last saw it
      // and runs again after a restart; the daemon keeps serving.
      spdlog::error("job {}: {}", id, e.what());
    } catch (...) {
      spdlog::error("job {}: unknown error", id);
    }
    {
      std::lock_guard lock(mutex_);
      running_.erase(id);
    }
    idle_.notify_all();
  }
}

}  // namespace meshmark::server
