#include "server/jobs/recover_jobs.hpp"

#include <gtest/gtest.h>

#include "server/store/job_transitions.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/server/storage_backends.hpp"
#include "tests/server/store_records.hpp"

namespace meshmark::server {
namespace {

// A prepare job (job_1) running at its first attempt, on every store backend.
class RecoverJobsBase : public ::testing::TestWithParam<test::StoreBackend> {
 protected:
  void SetUp() override {
    if (const std::string why = GetParam().absent(); !why.empty()) GTEST_SKIP() << why;
    store = GetParam().open(test::temp_dir("recover"), clock);
    store->insert_owner({"own_1", "o", "t"}, "h");
    store->insert_model(test::preparing_model("mdl_1", "own_1"), record("job_1", JobKind::prepare));
    start("job_1", 1);
  }
  JobRecord record(const std::string& id, JobKind kind) const {
    JobRecord j = test::job_record(id, "own_1", "mdl_1", kind);
    j.created_at = "2026-01-01T00:00:0" + id.substr(4) + "Z";
    return j;
  }
  // Starts the job `times` times (each start a new attempt, as after restarts).
  void start(const std::string& id, int times) {
    for (int k = 0; k < times; ++k) {
      JobRecord j = *store->job_by_id(id);
      start_job(j, clock.now_iso8601());
      ASSERT_EQ(store->start_job(j), JobWrite::written);
    }
  }
  std::vector<std::string> recovered_ids(const Lease& by) {
    std::vector<std::string> ids;
    for (const QueuedJob& q : recover_jobs(*store, clock, by, true)) ids.push_back(q.job_id);
    return ids;
  }
  std::vector<std::string> recovered_ids() { return recovered_ids(a); }
  test::ManualClock clock;
  // Two daemons on the store; the jobs here were accepted by `a` (with no lease: before leases).
  Lease a{"mmd_a", std::chrono::seconds(30)}, b{"mmd_b", std::chrono::seconds(30)};
  std::unique_ptr<Store> store;
};

class RecoverJobs : public RecoverJobsBase {};

TEST_P(RecoverJobs, RunningJobsAreQueuedAgainInTheirOrder) {
  store->insert_job(record("job_2", JobKind::embed));
  store->insert_job(record("job_3", JobKind::embed));
  start("job_3", 1);
  JobRecord done = *store->job_by_id("job_3");
  succeed_job(done, nlohmann::json::object(), clock.now_iso8601());
  ASSERT_EQ(store->finish_job(done), JobWrite::written);
  const std::vector<QueuedJob> queued = recover_jobs(*store, clock, a, true);
  ASSERT_EQ(queued.size(), 2u);
  EXPECT_EQ(queued[0].job_id, "job_1");
  EXPECT_TRUE(queued[0].prepares) << "what the queue needs to hold the model's other jobs back";
  EXPECT_EQ(queued[0].owner, "own_1");
  EXPECT_EQ(queued[1].job_id, "job_2");
  EXPECT_FALSE(queued[1].prepares);
  EXPECT_EQ(queued[1].model_id, "mdl_1");
  EXPECT_EQ(store->job_by_id("job_1")->state, JobState::queued);
  EXPECT_EQ(store->job_by_id("job_1")->attempts, 1) << "requeued at the attempt it had";
  EXPECT_EQ(store->job_by_id("job_3")->state, JobState::succeeded);
}

TEST_P(RecoverJobs, AJobInterruptedTooOftenFailsAndSoDoesItsModel) {
  start("job_1", kMaxJobAttempts - 1);
  EXPECT_TRUE(recovered_ids().empty());
  const auto failed = store->job_by_id("job_1");
  EXPECT_EQ(failed->state, JobState::failed);
  EXPECT_NE(failed->error.find("interrupted"), std::string::npos);
  EXPECT_EQ(store->model_by_id("mdl_1")->state, ModelState::failed);
}

// Daemon a holds job_1 and renews its lease; b takes it over only once a stops renewing, and then
// only b does.
TEST_P(RecoverJobs, AJobIsTakenOverOnlyAfterItsDaemonStoppedRenewingItsLease) {
  ASSERT_EQ(recovered_ids(a), (std::vector<std::string>{"job_1"})) << "a's own job, at a's start";
  start("job_1", 1);  // a runs it again (attempt 2)
  clock.advance(std::chrono::seconds(20));
  EXPECT_TRUE(recover_jobs(*store, clock, b, false).empty()) << "a's lease still runs";
  store->renew_leases(a.owner, a.until(clock));
  clock.advance(std::chrono::seconds(20));
  EXPECT_TRUE(recover_jobs(*store, clock, b, false).empty()) << "a renewed it";
  clock.advance(std::chrono::seconds(11));  // a stopped renewing 31 s ago
  const std::vector<QueuedJob> taken = recover_jobs(*store, clock, b, false);
  ASSERT_EQ(taken.size(), 1u);
  const JobRecord job = *store->job_by_id("job_1");
  EXPECT_EQ(job.lease_owner, "mmd_b");
  EXPECT_EQ(job.state, JobState::queued) << "b runs it again";
  EXPECT_EQ(job.attempts, 2) << "the next start is attempt 3, which fences a's writes";
  EXPECT_TRUE(recover_jobs(*store, clock, a, false).empty()) << "taken once";
  EXPECT_TRUE(recover_jobs(*store, clock, b, false).empty());
}

TEST_P(RecoverJobs, ALostWorkersWritesAreFencedAfterATakeOver) {
  recovered_ids(a);
  start("job_1", 1);
  JobRecord on_a = *store->job_by_id("job_1");
  clock.advance(std::chrono::seconds(31));
  ASSERT_EQ(recover_jobs(*store, clock, b, false).size(), 1u);
  start("job_1", 1);  // b's worker
  on_a.progress = 0.9;
  EXPECT_EQ(store->save_progress(on_a), JobWrite::lost);
  succeed_job(on_a, nlohmann::json::object(), clock.now_iso8601());
  EXPECT_EQ(store->finish_job(on_a), JobWrite::lost);
  EXPECT_EQ(store->model_by_id("mdl_1")->state, ModelState::preparing) << "only b's end will count";
}

INSTANTIATE_TEST_SUITE_P(Backends, RecoverJobs, ::testing::ValuesIn(test::store_backends()),
                         [](const auto& info) { return test::backend_name(info.param); });

class CancelJob : public RecoverJobsBase {};

TEST_P(CancelJob, AQueuedPrepareIsCanceledWithItsModel) {
  store->insert_model(test::preparing_model("mdl_2", "own_1"),
                      test::job_record("job_2", "own_1", "mdl_2", JobKind::prepare));
  EXPECT_EQ(store->cancel_job("own_1", "job_2"), CancelOutcome::canceled);
  EXPECT_EQ(store->job_by_id("job_2")->state, JobState::canceled);
  EXPECT_EQ(store->model_by_id("mdl_2")->state, ModelState::failed);
  EXPECT_EQ(store->model_by_id("mdl_2")->error, kPreparationCanceledError);
  EXPECT_EQ(store->cancel_job("own_1", "job_2"), CancelOutcome::finished);
}

TEST_P(CancelJob, ARunningJobKeepsItsRequestThroughProgressAndARestart) {
  EXPECT_EQ(store->cancel_job("own_1", "job_1"), CancelOutcome::requested);
  JobRecord j = *store->job_by_id("job_1");
  EXPECT_TRUE(j.cancel_requested);
  j.progress = 0.5;
  store->save_progress(j);  // the worker's progress must not erase the request
  EXPECT_TRUE(store->job_by_id("job_1")->cancel_requested);
  EXPECT_TRUE(recovered_ids().empty());  // not run again
  EXPECT_EQ(store->job_by_id("job_1")->state, JobState::canceled);
  EXPECT_EQ(store->model_by_id("mdl_1")->state, ModelState::failed);
}

TEST_P(CancelJob, AQueuedEmbedTakesItsPendingCopyWithIt) {
  JobRecord embed = record("job_2", JobKind::embed);
  ASSERT_TRUE(store->insert_embedding({"emb_1", "mdl_1", "own_1", "ab", "shop", "job_2", {}, "t"}, embed));
  EXPECT_EQ(store->cancel_job("own_1", "job_2"), CancelOutcome::canceled);
  EXPECT_TRUE(store->embeddings("mdl_1").empty()) << "a copy never made frees its payload";
}

TEST_P(CancelJob, AWorkerOnAnotherDaemonSeesTheCancelAtItsNextProgress) {
  JobRecord running = *store->job_by_id("job_1");
  running.progress = 0.2;
  ASSERT_EQ(store->save_progress(running), JobWrite::written);
  ASSERT_EQ(store->cancel_job("own_1", "job_1"), CancelOutcome::requested);
  running.progress = 0.3;
  EXPECT_EQ(store->save_progress(running), JobWrite::lost) << "the runner stops as canceled";
  cancel_job(running, clock.now_iso8601());
  EXPECT_EQ(store->finish_job(running), JobWrite::written);
  EXPECT_EQ(store->job_by_id("job_1")->state, JobState::canceled);
}

TEST_P(CancelJob, AnotherOwnersJobIsNotFound) {
  EXPECT_EQ(store->cancel_job("own_2", "job_1"), CancelOutcome::not_found);
  EXPECT_EQ(store->cancel_job("own_1", "job_404"), CancelOutcome::not_found);
  EXPECT_FALSE(store->job_by_id("job_1")->cancel_requested);
}

INSTANTIATE_TEST_SUITE_P(Backends, CancelJob, ::testing::ValuesIn(test::store_backends()),
                         [](const auto& info) { return test::backend_name(info.param); });

}  // namespace
}  // namespace meshmark::server
