#include "server/jobs/recover_jobs.hpp"

#include <gtest/gtest.h>

#include "server/store/sqlite_store.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/server/store_records.hpp"

namespace meshmark::server {
namespace {

class RecoverJobsBase : public ::testing::Test {
 protected:
  void SetUp() override {
    store.insert_owner({"own_1", "o", "t"}, "h");
    const ModelRecord m = test::preparing_model("mdl_1", "own_1");
    insert("job_1", JobKind::prepare, JobState::running, 1, &m);
  }
  void insert(const std::string& id, JobKind kind, JobState state, int attempts, const ModelRecord* model = nullptr) {
    JobRecord j = test::job_record(id, "own_1", "mdl_1", kind);
    j.created_at = "2026-01-01T00:00:0" + id.substr(4) + "Z";
    if (model) store.insert_model(*model, j);
    else store.insert_job(j);
    j.state = state;
    j.attempts = attempts;
    store.update_job(j);
  }
  SqliteStore store{test::temp_dir("recover") / "db"};
};

class RecoverJobs : public RecoverJobsBase {};

TEST_F(RecoverJobs, RunningJobsAreQueuedAgainInTheirOrder) {
  insert("job_2", JobKind::embed, JobState::queued, 0);
  insert("job_3", JobKind::embed, JobState::succeeded, 1);
  EXPECT_EQ(recover_jobs(store), (std::vector<std::string>{"job_1", "job_2"}));
  EXPECT_EQ(store.job_by_id("job_1")->state, JobState::queued);
  EXPECT_EQ(store.job_by_id("job_3")->state, JobState::succeeded);
}

TEST_F(RecoverJobs, AJobInterruptedTooOftenFailsAndSoDoesItsModel) {
  JobRecord j = *store.job_by_id("job_1");
  j.attempts = kMaxJobAttempts;
  store.update_job(j);
  EXPECT_TRUE(recover_jobs(store).empty());
  const auto failed = store.job_by_id("job_1");
  EXPECT_EQ(failed->state, JobState::failed);
  EXPECT_NE(failed->error.find("interrupted"), std::string::npos);
  EXPECT_EQ(store.model_by_id("mdl_1")->state, ModelState::failed);
}

}  // namespace
}  // namespace meshmark::server

namespace meshmark::server {
namespace {

class CancelJob : public RecoverJobsBase {};

TEST_F(CancelJob, AQueuedPrepareIsCanceledWithItsModel) {
  JobRecord j = *store.job_by_id("job_1");
  j.state = JobState::queued;
  store.update_job(j);
  EXPECT_EQ(store.cancel_job("own_1", "job_1", "now"), CancelOutcome::canceled);
  EXPECT_EQ(store.job_by_id("job_1")->state, JobState::canceled);
  EXPECT_EQ(store.model_by_id("mdl_1")->state, ModelState::failed);
  EXPECT_EQ(store.cancel_job("own_1", "job_1", "now"), CancelOutcome::finished);
}

TEST_F(CancelJob, ARunningJobKeepsItsRequestThroughUpdatesAndARestart) {
  EXPECT_EQ(store.cancel_job("own_1", "job_1", "now"), CancelOutcome::requested);
  JobRecord j = *store.job_by_id("job_1");
  EXPECT_TRUE(j.cancel_requested);
  j.progress = 0.5;
  store.update_job(j);  // the worker's progress must not erase the request
  EXPECT_TRUE(store.job_by_id("job_1")->cancel_requested);
  EXPECT_TRUE(recover_jobs(store).empty());  // not run again
  EXPECT_EQ(store.job_by_id("job_1")->state, JobState::canceled);
  EXPECT_EQ(store.model_by_id("mdl_1")->state, ModelState::failed);
}

TEST_F(CancelJob, AnotherOwnersJobIsNotFound) {
  EXPECT_EQ(store.cancel_job("own_2", "job_1", "now"), CancelOutcome::not_found);
  EXPECT_EQ(store.cancel_job("own_1", "job_404", "now"), CancelOutcome::not_found);
  EXPECT_FALSE(store.job_by_id("job_1")->cancel_requested);
}

}  // namespace
}  // namespace meshmark::server
