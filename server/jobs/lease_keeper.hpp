#pragma once
// The heartbeat of a daemon's jobs: every third of a lease it renews the leases of the jobs it
// holds, and takes over the jobs whose lease ran out (their daemon died) into its queue. A daemon
// that loses its store for longer than a lease loses its jobs to the others; the attempt number
// keeps it from writing over them when it comes back (Store::start_job).

#include <condition_variable>
#include <mutex>
#include <thread>

#include "server/jobs/recover_jobs.hpp"

namespace meshmark::server {

class LeaseKeeper {
 public:
  LeaseKeeper(Store& store, JobQueue& queue, const Clock& clock, Lease lease);
  ~LeaseKeeper();  ///< stops the heartbeat (the jobs' leases then run out unless renewed elsewhere)
  LeaseKeeper(const LeaseKeeper&) = delete;
  LeaseKeeper& operator=(const LeaseKeeper&) = delete;

  /// One beat, now: renew, then take over (what the thread does every third of a lease).
  void beat();

 private:
  Store& store_;
  JobQueue& queue_;
  const Clock& clock_;
  const Lease lease_;
  std::mutex mutex_;
  std::condition_variable stop_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace meshmark::server
