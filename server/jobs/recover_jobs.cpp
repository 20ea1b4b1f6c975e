#include "server/jobs/recover_jobs.hpp"

#include "server/clock.hpp"

namespace meshmark::server {

void finish_canceled(Store& store, JobRecord job) {
  job.state = "canceled";
  job.error = "canceled";
  job.finished_at = now_iso8601();
  store.update_job(job);
  if (job.kind == "prepare") store.set_model_state(job.model_id, "failed", "its preparation was canceled");
}

std::vector<std::string> recover_jobs(Store& store) {
  for (JobRecord job : store.jobs_in_state("running")) {
    if (job.cancel_requested) {  // acknowledged before the stop: honour it
      finish_canceled(store, job);
      continue;
    }
    if (job.attempts >= kMaxJobAttempts) {
      job.state = "failed";
      job.error = "interrupted " + std::to_string(job.attempts) + " times (the daemon stopped while it ran)";
      job.finished_at = now_iso8601();
      store.update_job(job);
      if (job.kind == "prepare") store.set_model_state(job.model_id, "failed", job.error);
      continue;
    }
    job.state = "queued";
    job.stage = "queued";
    store.update_job(job);
  }
  std::vector<std::string> queued;
  for (const JobRecord& job : store.jobs_in_state("queued")) queued.push_back(job.id);
  return queued;
}

}  // namespace meshmark::server
