#include "server/jobs/recover_jobs.hpp"

#include "server/store/job_transitions.hpp"

namespace meshmark::server {

void finish_canceled(Store& store, JobRecord job, const Clock& clock) {
  cancel_job(job, clock.now_iso8601());
  store.finish_job(job);
}

QueuedJob queued_job(const JobRecord& job) {
  return {job.id, job.owner_id, job.model_id, job.kind() == JobKind::prepare};
}

namespace {

// A running job whose worker is gone: false when it ends here instead of running again.
bool requeue_interrupted(Store& store, JobRecord job, const Clock& clock) {
  if (job.cancel_requested) {  // acknowledged before the stop: honour it
    finish_canceled(store, job, clock);
    return false;
  }
  if (job.attempts >= kMaxJobAttempts) {
    fail_job(job, "interrupted " + std::to_string(job.attempts) + " times (its daemon stopped while it ran)",
             clock.now_iso8601());
    store.finish_job(job);
    return false;
  }
  requeue_job(job);
  return store.requeue_job(job) == JobWrite::written;
}

}  // namespace

std::vector<QueuedJob> recover_jobs(Store& store, const Clock& clock, const Lease& lease, bool at_start) {
  std::vector<QueuedJob> queued;
  for (const JobRecord& job : store.take_over_jobs(lease.owner, clock.now_iso8601(), lease.until(clock), at_start))
    if (job.state == JobState::queued || requeue_interrupted(store, job, clock)) queued.push_back(queued_job(job));
  return queued;
}

}  // namespace meshmark::server
