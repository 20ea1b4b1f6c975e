#pragma once
// Taking over work nobody runs any more: at start-up, the jobs this daemon held before it stopped
// (a crash, a restart); at any time, the jobs whose daemon's lease ran out (it died, or lost its
// store). Each such job is queued here again — a running one after an honoured cancel, or after
// too many tries, ends instead.

#include <chrono>
#include <string>
#include <vector>

#include "server/clock.hpp"
#include "server/jobs/job_queue.hpp"
#include "server/store/store.hpp"

namespace meshmark::server {

/// A job is tried at most this many times; then it is marked failed rather than run again.
constexpr int kMaxJobAttempts = 3;

/// Who holds the jobs this daemon queues and runs, and for how long each renewal lasts.
struct Lease {
  std::string owner;  ///< this daemon's instance id (stable for its data folder)
  std::chrono::seconds duration{30};
  /// When a lease taken or renewed now runs out.
  std::string until(const Clock& clock) const { return iso8601(clock.now() + duration); }
};

/// Ends a job whose cancel was acknowledged (and, for a prepare job, fails its model).
void finish_canceled(Store& store, JobRecord job, const Clock& clock);

/// Takes over the jobs whose lease ran out (and, `at_start`, this daemon's own from before its
/// start): running ones go back to queued (or fail after kMaxJobAttempts, or end canceled), and
/// all of them are returned, oldest first, as the queue takes them.
std::vector<QueuedJob> recover_jobs(Store& store, const Clock& clock, const Lease& lease, bool at_start);

/// How the queue knows a job.
QueuedJob queued_job(const JobRecord& job);

}  // namespace meshmark::server
