#include "server/store/job_transitions.hpp"

#include <stdexcept>

namespace meshmark::server {

namespace {

void require(const JobRecord& job, bool allowed, const char* move) {
  if (!allowed) throw std::logic_error("job " + job.id + " cannot " + move + " from state " + to_string(job.state));
}

void finish(JobRecord& job, JobState state, const std::string& error, const std::string& now) {
  job.state = state;
  job.error = error;
  job.finished_at = now;
}

}  // namespace

void start_job(JobRecord& job, const std::string& now) {
  require(job, job.state == JobState::queued || job.state == JobState::running, "start");
  job.state = JobState::running;
  job.attempts += 1;
  job.started_at = now;
  job.stage = "starting";
}

void succeed_job(JobRecord& job, nlohmann::json result, const std::string& now) {
  require(job, job.state == JobState::running, "succeed");
  finish(job, JobState::succeeded, "", now);
  job.result = std::move(result);
  job.progress = 1;
  job.stage = "done";
}

void fail_job(JobRecord& job, const std::string& error, const std::string& now) {
  require(job, !is_final(job.state), "fail");
  finish(job, JobState::failed, error, now);
}

void cancel_job(JobRecord& job, const std::string& now) {
  require(job, !is_final(job.state), "be canceled");
  finish(job, JobState::canceled, kCanceledError, now);
}

void requeue_job(JobRecord& job) {
  require(job, job.state == JobState::running, "be requeued");
  job.state = JobState::queued;
  job.stage = to_string(JobState::queued);
}

ModelOutcome model_outcome(const JobRecord& job) {
  require(job, job.kind() == JobKind::prepare && is_final(job.state), "decide its model's state");
  switch (job.state) {
    case JobState::succeeded:
      return {ModelState::ready, ""};
    case JobState::canceled:
      return {ModelState::failed, kPreparationCanceledError};
    default:
      return {ModelState::failed, job.error};
  }
}

}  // namespace meshmark::server
