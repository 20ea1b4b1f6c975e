#pragma once
// A background thread that runs a task every interval until it is destroyed (the destructor
// waits for a run under way). The daemon's heartbeat and its housekeeping use one each.

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace meshmark::server {

class PeriodicTask {
 public:
  /// The first run is one interval from now. `task` must not throw.
  PeriodicTask(std::chrono::milliseconds interval, std::function<void()> task);
  ~PeriodicTask();
  PeriodicTask(const PeriodicTask&) = delete;
  PeriodicTask& operator=(const PeriodicTask&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable stop_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace meshmark::server
