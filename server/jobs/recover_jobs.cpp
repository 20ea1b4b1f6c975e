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

std::vector<QueuedJob> recover_jobs(Store& store, const Clock& clock) {
  for (JobRecord job : store.jobs_in_state(JobState::running)) {
    if (job.cancel_requested) {  // acknowledged before the stop: honour it
      finish_canceled(store, job, clock);
      continue;
    }
    if (job.attempts >= kMaxJobAttempts) {
      fail_job(job, "interrupted " + std::to_string(job.attempts) + " times (the daemon stopped while it ran)",
               clock.now_iso8601());
      store.finish_job(job);
      continue;
    }
    requeue_job(job);
    store.requeue_job(job);
  }
  std::vector<QueuedJob> queued;
  for (const JobRecord& job : store.jobs_in_state(JobState::queued)) queued.push_back(queued_job(job));
  return queued;
}

}  // namespace meshmark::server
