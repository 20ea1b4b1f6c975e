#pragma once
// What happens, at start-up, to work a crash or a restart interrupted.

#include <vector>

#include "server/clock.hpp"
#include "server/jobs/job_queue.hpp"
#include "server/store/store.hpp"

namespace meshmark::server {

/// A job is tried at most this many times; then it is marked failed rather than run again.
constexpr int kMaxJobAttempts = 3;

/// Ends a job whose cancel was acknowledged (and, for a prepare job, fails its model).
void finish_canceled(Store& store, JobRecord job, const Clock& clock);

/// Puts jobs left 'running' back to 'queued' (or marks them 'failed', and a model being prepared
/// with them, after kMaxJobAttempts), and returns all queued jobs, oldest first, as the queue
/// takes them.
std::vector<QueuedJob> recover_jobs(Store& store, const Clock& clock);

/// How the queue knows a job.
QueuedJob queued_job(const JobRecord& job);

}  // namespace meshmark::server
