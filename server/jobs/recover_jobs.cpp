#include "server/jobs/recover_jobs.hpp"

#include "server/clock.hpp"
#include "server/store/job_transitions.hpp"

namespace meshmark::server {

namespace {

// Writes a job that has just ended, and its model's state when it was a preparation.
void record_end(Store& store, const JobRecord& job) {
  store.update_job(job);
  if (job.kind != JobKind::prepare) return;
  const ModelOutcome model = model_outcome(job);
  store.set_model_state(job.model_id, model.state, model.error);
}

}  // namespace

void finish_canceled(Store& store, JobRecord job) {
  cancel_job(job, now_iso8601());
  record_end(store, job);
}

std::vector<std::string> recover_jobs(Store& store) {
  for (JobRecord job : store.jobs_in_state(JobState::running)) {
    if (job.cancel_requested) {  // acknowledged before the stop: honour it
      finish_canceled(store, job);
      continue;
    }
    if (job.attempts >= kMaxJobAttempts) {
      fail_job(job, "interrupted " + std::to_string(job.attempts) + " times (the daemon stopped while it ran)",
               now_iso8601());
      record_end(store, job);
      continue;
    }
    requeue_job(job);
    store.update_job(job);
  }
  std::vector<std::string> queued;
  for (const JobRecord& job : store.jobs_in_state(JobState::queued)) queued.push_back(job.id);
  return queued;
}

}  // namespace meshmark::server
