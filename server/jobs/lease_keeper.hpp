#pragma once
// The heartbeat of a daemon's jobs: every third of a lease it renews the leases of the jobs it
// holds, and takes over the jobs whose lease ran out (their daemon died) into its queue. A daemon
// that loses its store for longer than a lease loses its jobs to the others; the attempt number
// keeps it from writing over them when it comes back (Store::start_job).

#include "server/jobs/recover_jobs.hpp"
#include "server/periodic_task.hpp"

namespace meshmark::server {

class LeaseKeeper {
 public:
  LeaseKeeper(Store& store, JobQueue& queue, const Clock& clock, Lease lease);
  // Destroyed, it stops the heartbeat (the jobs' leases then run out unless renewed elsewhere).

  /// One beat, now: renew, then take over (what the thread does every third of a lease).
  void beat();

 private:
  Store& store_;
  JobQueue& queue_;
  const Clock& clock_;
  const Lease lease_;
  PeriodicTask heartbeat_;  // last: it stops before the members it uses go
};

}  // namespace meshmark::server
