#pragma once
// Every move of a job between states, and what its model's state becomes, in one place: the
// runner, the recovery after a restart and each store backend apply these and nothing else.
//
//   queued ──start──▶ running ──succeed──▶ succeeded      (running ──start──▶ running: a retry
//                                                           after the store was full)
//     │                 │ ├────fail─────▶ failed
//     └──cancel──▶ canceled ◀──cancel──┘ └──requeue (restart)──▶ queued
//
// A prepare job takes its model with it: succeeded → model ready, failed or canceled → model
// failed with the job's error.

#include <string>

#include <nlohmann/json.hpp>
#include "server/store/records.hpp"

namespace meshmark::server {

/// The error a canceled job reports, and its model's when it was a preparation.
inline constexpr const char* kCanceledError = "canceled";
inline constexpr const char* kPreparationCanceledError = "its preparation was canceled";

/// queued → running: one more attempt, stage "starting". Also running → running: the queue runs
/// a job again when the full store refused its outcome (the store still says running). Throws
/// std::logic_error from a final state.
void start_job(JobRecord& job, const std::string& now);
/// running → succeeded with its result.
void succeed_job(JobRecord& job, nlohmann::json result, const std::string& now);
/// queued | running → failed with the error shown to its owner.
void fail_job(JobRecord& job, const std::string& error, const std::string& now);
/// queued | running → canceled.
void cancel_job(JobRecord& job, const std::string& now);
/// running → queued: the daemon stopped while it ran and it will run again.
void requeue_job(JobRecord& job);

/// The state a model takes when its prepare job ends in `job.state` (a final state).
struct ModelOutcome {
  ModelState state;
  std::string error;
};
ModelOutcome model_outcome(const JobRecord& prepare_job);

}  // namespace meshmark::server
