// The moves between job states, one invariant per test.

#include "server/store/job_transitions.hpp"

#include <gtest/gtest.h>

#include "tests/server/store_records.hpp"

namespace meshmark::server {
namespace {

JobRecord queued(JobKind kind = JobKind::prepare) {
  JobRecord j;
  j.id = "job_1";
  j.spec = test::job_spec(kind);
  return j;
}

TEST(JobTransitions, StartingCountsAnAttempt) {
  JobRecord j = queued();
  start_job(j, "t0");
  EXPECT_EQ(j.state, JobState::running);
  EXPECT_EQ(j.attempts, 1);
  EXPECT_EQ(j.started_at, "t0");
  EXPECT_EQ(j.stage, "starting");
}

TEST(JobTransitions, SucceedingKeepsTheResultAndEndsTheJob) {
  JobRecord j = queued();
  start_job(j, "t0");
  succeed_job(j, {{"x", 1}}, "t1");
  EXPECT_EQ(j.state, JobState::succeeded);
  EXPECT_EQ(j.result["x"], 1);
  EXPECT_EQ(j.progress, 1.0);
  EXPECT_EQ(j.finished_at, "t1");
  EXPECT_TRUE(j.finished());
}

TEST(JobTransitions, ARunningJobTheFullStoreRefusedStartsAgainAsAnotherAttempt) {
  JobRecord j = queued();
  start_job(j, "t0");
  start_job(j, "t1");
  EXPECT_EQ(j.state, JobState::running);
  EXPECT_EQ(j.attempts, 2);
}

TEST(JobTransitions, AFinishedJobCannotMoveAgain) {
  JobRecord j = queued();
  start_job(j, "t0");
  fail_job(j, "broken", "t1");
  EXPECT_THROW(start_job(j, "t2"), std::logic_error);
  EXPECT_THROW(succeed_job(j, {}, "t2"), std::logic_error);
  EXPECT_THROW(cancel_job(j, "t2"), std::logic_error);
  EXPECT_EQ(j.error, "broken");
}

TEST(JobTransitions, OnlyARunningJobSucceedsOrIsRequeued) {
  JobRecord j = queued();
  EXPECT_THROW(succeed_job(j, {}, "t"), std::logic_error);
  EXPECT_THROW(requeue_job(j), std::logic_error);
  start_job(j, "t0");
  requeue_job(j);
  EXPECT_EQ(j.state, JobState::queued);
  EXPECT_EQ(j.stage, "queued");
  EXPECT_EQ(j.attempts, 1) << "a requeued job keeps the count of its attempts";
}

TEST(JobTransitions, APreparationsEndDecidesItsModel) {
  JobRecord ok = queued(), failed = queued(), canceled = queued();
  start_job(ok, "t");
  succeed_job(ok, {}, "t");
  fail_job(failed, "the mesh has a hole", "t");
  cancel_job(canceled, "t");
  EXPECT_EQ(model_outcome(ok).state, ModelState::ready);
  EXPECT_EQ(model_outcome(failed).state, ModelState::failed);
  EXPECT_EQ(model_outcome(failed).error, "the mesh has a hole");
  EXPECT_EQ(model_outcome(canceled).state, ModelState::failed);
  EXPECT_EQ(model_outcome(canceled).error, kPreparationCanceledError);
}

TEST(JobTransitions, OnlyAFinishedPreparationHasAModelOutcome) {
  JobRecord running = queued();
  start_job(running, "t");
  EXPECT_THROW(model_outcome(running), std::logic_error);
  JobRecord embed = queued(JobKind::embed);
  cancel_job(embed, "t");
  EXPECT_THROW(model_outcome(embed), std::logic_error);
}

}  // namespace
}  // namespace meshmark::server
