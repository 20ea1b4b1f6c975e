// The contract of every Store backend (storage_backends.hpp): records, owner scoping, and the
// fenced moves of a job.
#include "server/store/store.hpp"

#include <gtest/gtest.h>
#include <libpq-fe.h>

#include <condition_variable>

#include <mutex>
#include <set>
#include <thread>

#include "server/store/job_transitions.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/server/storage_backends.hpp"
#include "tests/server/store_records.hpp"

namespace meshmark::server {
namespace {

class StoreContract : public ::testing::TestWithParam<test::StoreBackend> {
 protected:
  void SetUp() override {
    if (const std::string why = GetParam().absent(); !why.empty()) GTEST_SKIP() << why;
    store = open();
    store->insert_owner(owner, "hash-1");
  }
  std::unique_ptr<Store> open() { return GetParam().open(place, clock); }
  ModelRecord model() const {
    ModelRecord m = test::preparing_model("mdl_1", owner.id);
    m.name = "bunny";
    m.format = "obj";
    m.report = {{"valid", true}};
    m.created_at = m.updated_at = "2026-01-01T00:00:00Z";
    return m;
  }
  JobRecord job(const std::string& id, JobKind kind) const {
    JobRecord j = test::job_record(id, owner.id, "mdl_1", kind);
    j.created_at = "2026-01-01T00:00:0" + id.substr(id.size() - 1) + "Z";
    return j;
  }
  // An embed job and the copy it makes, stored together.
  JobRecord insert_copy(const std::string& job_id, const std::string& embedding_id, const std::string& payload) {
    JobRecord j = job(job_id, JobKind::embed);
    j.spec = test::job_spec(JobKind::embed, embedding_id);
    const EmbeddingRecord e{embedding_id, "mdl_1", owner.id, payload, "shop", job_id, {{"scheme", "spread"}}, "t"};
    EXPECT_TRUE(store->insert_embedding(e, j));
    return j;
  }
  JobRecord started(JobRecord j) {
    start_job(j, clock.now_iso8601());
    EXPECT_EQ(store->start_job(j), JobWrite::written);
    return j;
  }

  test::ManualClock clock;
  std::filesystem::path place = test::temp_dir("store");
  OwnerRecord owner{"own_1", "Studio", "2026-01-01T00:00:00Z"};
  std::unique_ptr<Store> store;
};

TEST_P(StoreContract, RecordsSurviveReopening) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  insert_copy("job_2", "emb_1", "ab");
  store.reset();
  store = open();
  ASSERT_TRUE(store->owner_by_key_hash("hash-1"));
  EXPECT_EQ(store->owner_by_key_hash("hash-1")->name, "Studio");
  ASSERT_TRUE(store->model(owner.id, "mdl_1"));
  EXPECT_EQ(store->model(owner.id, "mdl_1")->report.value("valid", false), true);
  EXPECT_EQ(store->embeddings("mdl_1").size(), 1u);
  EXPECT_EQ(store->jobs_in_state(JobState::queued).size(), 2u);
}

TEST_P(StoreContract, AJobsSpecIsReadBackAsWritten) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  const JobRecord embed = insert_copy("job_2", "emb_1", "ab");
  JobRecord detect = job("job_3", JobKind::detect);
  store->insert_job(detect);
  EXPECT_EQ(job_spec_json(store->job_by_id("job_2")->spec), job_spec_json(embed.spec));
  EXPECT_EQ(job_spec_json(store->job_by_id("job_3")->spec), job_spec_json(detect.spec));
  EXPECT_EQ(store->job_by_id("job_1")->kind(), JobKind::prepare);
}

TEST_P(StoreContract, AnotherOwnerFindsNothing) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  EXPECT_FALSE(store->model("own_2", "mdl_1"));
  EXPECT_FALSE(store->job("own_2", "job_1"));
  EXPECT_TRUE(store->models("own_2").empty());
  EXPECT_FALSE(store->delete_model("own_2", "mdl_1"));
  EXPECT_TRUE(store->model(owner.id, "mdl_1"));
}

TEST_P(StoreContract, ADuplicatePayloadStoresNeitherTheEmbeddingNorItsJob) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  insert_copy("job_2", "emb_1", "ab");
  JobRecord again = job("job_3", JobKind::embed);
  EXPECT_FALSE(store->insert_embedding({"emb_2", "mdl_1", owner.id, "ab", "shop", "job_3", {}, "t"}, again));
  EXPECT_EQ(store->embeddings("mdl_1").size(), 1u);
  EXPECT_FALSE(store->job_by_id("job_3"));
}

TEST_P(StoreContract, DeletingAModelRemovesItsEmbeddingsAndAllItsJobsAndNamesThem) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  JobRecord prepare = started(job("job_1", JobKind::prepare));
  succeed_job(prepare, nlohmann::json::object(), clock.now_iso8601());
  ASSERT_EQ(store->finish_job(prepare), JobWrite::written);
  insert_copy("job_2", "emb_1", "ab");  // still queued
  const auto jobs = store->delete_model(owner.id, "mdl_1");
  ASSERT_TRUE(jobs);
  EXPECT_EQ(std::set<std::string>(jobs->begin(), jobs->end()), (std::set<std::string>{"job_1", "job_2"}));
  EXPECT_FALSE(store->model(owner.id, "mdl_1"));
  EXPECT_TRUE(store->embeddings("mdl_1").empty());
  EXPECT_FALSE(store->job_by_id("job_1"));
  EXPECT_FALSE(store->job_by_id("job_2"));
}

TEST_P(StoreContract, APrepareJobsEndDecidesItsModelInTheSameWrite) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  JobRecord j = started(job("job_1", JobKind::prepare));
  clock.advance(std::chrono::seconds(5));
  fail_job(j, "the mesh has no faces", clock.now_iso8601());
  ASSERT_EQ(store->finish_job(j), JobWrite::written);
  const auto m = store->model_by_id("mdl_1");
  EXPECT_EQ(m->state, ModelState::failed);
  EXPECT_EQ(m->error, "the mesh has no faces");
  EXPECT_EQ(m->updated_at, "2026-01-01T00:00:05.000Z") << "the store's clock, the job's end";
  EXPECT_EQ(store->job_by_id("job_1")->finished_at, "2026-01-01T00:00:05.000Z");
}

TEST_P(StoreContract, AnEmbeddingNeverMadeIsForgottenAndFreesItsPayload) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  JobRecord first = started(insert_copy("job_2", "emb_1", "ab"));
  EXPECT_EQ(store->embeddings("mdl_1").at(0).state, EmbeddingState::pending);
  fail_job(first, "internal error", clock.now_iso8601());
  ASSERT_EQ(store->finish_job(first), JobWrite::written);
  EXPECT_TRUE(store->embeddings("mdl_1").empty());
  JobRecord second = started(insert_copy("job_3", "emb_2", "ab"));
  succeed_job(second, {{"payload", "ab"}}, clock.now_iso8601());
  ASSERT_EQ(store->finish_job(second), JobWrite::written);
  EXPECT_EQ(store->embeddings("mdl_1").at(0).state, EmbeddingState::ready);
}

TEST_P(StoreContract, AFinishedJobIsReadBack) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  JobRecord j = started(job("job_1", JobKind::prepare));
  succeed_job(j, {{"seconds", 1.5}}, clock.now_iso8601());
  ASSERT_EQ(store->finish_job(j), JobWrite::written);
  const auto read = store->job(owner.id, "job_1");
  ASSERT_TRUE(read);
  EXPECT_EQ(read->state, JobState::succeeded);
  EXPECT_EQ(read->result.value("seconds", 0.0), 1.5);
  EXPECT_EQ(read->attempts, 1);
  EXPECT_EQ((store->job_counts()[{"prepare", "succeeded"}]), 1);
}

// The fence: a worker whose attempt is no longer the job's writes nothing.
TEST_P(StoreContract, OnlyOneStartOfAnAttemptWins) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  JobRecord a = *store->job_by_id("job_1");
  JobRecord b = a;
  start_job(a, clock.now_iso8601());
  start_job(b, clock.now_iso8601());
  EXPECT_EQ(store->start_job(a), JobWrite::written);
  EXPECT_EQ(store->start_job(b), JobWrite::lost) << "the same attempt started twice";
  EXPECT_EQ(store->job_by_id("job_1")->attempts, 1);
}

TEST_P(StoreContract, AWorkerThatLostItsJobWritesNothing) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  JobRecord old_attempt = started(job("job_1", JobKind::prepare));
  JobRecord new_attempt = old_attempt;
  start_job(new_attempt, clock.now_iso8601());  // the job was taken over (attempt 2)
  ASSERT_EQ(store->start_job(new_attempt), JobWrite::written);
  old_attempt.progress = 0.7;
  old_attempt.stage = "sample";
  EXPECT_EQ(store->save_progress(old_attempt), JobWrite::lost);
  succeed_job(old_attempt, {{"seconds", 1}}, clock.now_iso8601());
  EXPECT_EQ(store->finish_job(old_attempt), JobWrite::lost);
  const auto now = store->job_by_id("job_1");
  EXPECT_EQ(now->state, JobState::running);
  EXPECT_EQ(now->attempts, 2);
  EXPECT_NE(now->stage, "sample");
  EXPECT_EQ(store->model_by_id("mdl_1")->state, ModelState::preparing) << "the model follows only the written end";
}

TEST_P(StoreContract, AJobEndsOnce) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  JobRecord j = started(job("job_1", JobKind::prepare));
  JobRecord twice = j;
  succeed_job(j, nlohmann::json::object(), clock.now_iso8601());
  fail_job(twice, "late", clock.now_iso8601());
  EXPECT_EQ(store->finish_job(j), JobWrite::written);
  EXPECT_EQ(store->finish_job(twice), JobWrite::lost);
  EXPECT_EQ(store->job_by_id("job_1")->state, JobState::succeeded);
  EXPECT_EQ(store->model_by_id("mdl_1")->state, ModelState::ready);
}

TEST_P(StoreContract, AWriteToADeletedJobSaysItIsGone) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  JobRecord j = started(job("job_1", JobKind::prepare));
  ASSERT_TRUE(store->delete_model(owner.id, "mdl_1"));
  EXPECT_EQ(store->save_progress(j), JobWrite::gone);
  succeed_job(j, nlohmann::json::object(), clock.now_iso8601());
  EXPECT_EQ(store->finish_job(j), JobWrite::gone);
}

TEST_P(StoreContract, TheFirstMasterKeyFingerprintStays) {
  EXPECT_EQ(store->record_master_key_fingerprint("aaaa"), "aaaa");
  EXPECT_EQ(store->record_master_key_fingerprint("bbbb"), "aaaa") << "a second key does not replace the first";
  store.reset();
  store = open();
  EXPECT_EQ(store->record_master_key_fingerprint("bbbb"), "aaaa");
}

// Jobs daemon "a" accepted and holds; "b" is idle.
TEST_P(StoreContract, AnIdleDaemonClaimsTheOldestRunnableJobAnotherHolds) {
  JobRecord prepare = job("job_1", JobKind::prepare);
  prepare.lease_owner = "mmd_a";
  store->insert_model(model(), prepare);
  JobRecord embed = job("job_2", JobKind::embed);
  embed.lease_owner = "mmd_a";
  store->insert_job(embed);
  EXPECT_FALSE(store->claim_queued_job("mmd_a", "t")) << "not its own";
  const auto first_claim = store->claim_queued_job("mmd_b", "t");
  ASSERT_TRUE(first_claim);
  EXPECT_EQ(first_claim->id, "job_1");
  EXPECT_EQ(first_claim->lease_owner, "mmd_b");
  EXPECT_FALSE(store->claim_queued_job("mmd_c", "t")) << "job_2's model is still being prepared";
  JobRecord prepared = started(*first_claim);
  succeed_job(prepared, nlohmann::json::object(), clock.now_iso8601());
  ASSERT_EQ(store->finish_job(prepared), JobWrite::written);
  const auto second = store->claim_queued_job("mmd_c", "t");
  ASSERT_TRUE(second);
  EXPECT_EQ(second->id, "job_2");
}

TEST_P(StoreContract, AJobAnotherDaemonClaimedIsNotStartedByItsFormerHolder) {
  JobRecord prepare = job("job_1", JobKind::prepare);
  prepare.lease_owner = "mmd_a";
  store->insert_model(model(), prepare);
  JobRecord on_a = *store->job_by_id("job_1");
  ASSERT_TRUE(store->claim_queued_job("mmd_b", "t"));
  start_job(on_a, clock.now_iso8601());
  EXPECT_EQ(store->start_job(on_a), JobWrite::lost) << "b holds it now";
  JobRecord on_b = *store->job_by_id("job_1");
  start_job(on_b, clock.now_iso8601());
  EXPECT_EQ(store->start_job(on_b), JobWrite::written);
  EXPECT_EQ(store->job_by_id("job_1")->attempts, 1);
}

// Four daemons claiming at once from 40 queued jobs: each job is claimed exactly once.
TEST_P(StoreContract, ConcurrentClaimsNeverTakeAJobTwice) {
  store->insert_model(model(), job("job_0", JobKind::prepare));
  JobRecord prepare = started(job("job_0", JobKind::prepare));
  succeed_job(prepare, nlohmann::json::object(), clock.now_iso8601());
  store->finish_job(prepare);
  for (int k = 1; k <= 40; ++k) store->insert_job(job("job_d" + std::to_string(k), JobKind::detect));
  std::mutex mutex;
  std::vector<std::string> claimed;
  std::vector<std::thread> daemons;
  for (int d = 0; d < 4; ++d)
    daemons.emplace_back([&, d] {
      while (const auto j = store->claim_queued_job("mmd_" + std::to_string(d), "t")) {
        JobRecord running = *j;
        start_job(running, "t");
        ASSERT_EQ(store->start_job(running), JobWrite::written) << running.id;  // the claim holds it: started once
        std::lock_guard lock(mutex);
        claimed.push_back(j->id);
      }
    });
  for (auto& t : daemons) t.join();
  EXPECT_EQ(claimed.size(), 40u);
  EXPECT_EQ(std::set<std::string>(claimed.begin(), claimed.end()).size(), 40u);
}

// Another daemon on the store hears each announcement, also after its listening connection was
// cut; a store no other daemon shares has nothing to announce.
TEST_P(StoreContract, AnotherDaemonHearsOfClaimableJobs) {
  std::mutex mutex;
  std::condition_variable heard_again;
  int heard = 0;
  const std::unique_ptr<Store> other = open();
  const auto subscription = other->watch_claimable_jobs([&] {
    std::lock_guard lock(mutex);
    ++heard;
    heard_again.notify_all();
  });
  if (GetParam().name == "sqlite") {
    EXPECT_EQ(subscription, nullptr);
    store->announce_claimable_jobs();  // to nobody, harmlessly
    return;
  }
  ASSERT_NE(subscription, nullptr);
  const auto hears_announcement = [&] {
    std::unique_lock lock(mutex);
    heard_again.wait_for(lock, std::chrono::seconds(10), [&] { return heard > 0; });  // the listener is up
    const int before = heard;
    lock.unlock();
    store->announce_claimable_jobs();
    lock.lock();
    return heard_again.wait_for(lock, std::chrono::seconds(10), [&] { return heard > before; });
  };
  EXPECT_TRUE(hears_announcement());
  EXPECT_TRUE(hears_announcement());
  PGconn* admin = PQconnectdb(test::postgres_test_database(place).c_str());
  PQclear(PQexec(admin, "SELECT pg_terminate_backend(pid) FROM pg_stat_activity WHERE query LIKE 'LISTEN%'"));
  PQfinish(admin);
  EXPECT_TRUE(hears_announcement()) << "after the cut";
  EXPECT_TRUE(hears_announcement());
}

// The export of who received what spans the owner's models and no one else's; a model's jobs
// of one kind come oldest first.
TEST_P(StoreContract, AnOwnersCopiesAcrossModelsAndAModelsJobsOfAKind) {
  store->insert_model(model(), job("job_1", JobKind::prepare));
  insert_copy("job_2", "emb_1", "ab");
  ModelRecord second = model();
  second.id = "mdl_2";
  second.name = "dragon";
  JobRecord second_prepare = job("job_5", JobKind::prepare);
  second_prepare.model_id = "mdl_2";
  store->insert_model(second, second_prepare);
  JobRecord on_second = job("job_6", JobKind::embed);
  on_second.model_id = "mdl_2";
  on_second.spec = test::job_spec(JobKind::embed, "emb_2");
  ASSERT_TRUE(store->insert_embedding(
      {"emb_2", "mdl_2", owner.id, "cd", "museum", "job_6", {}, "u", EmbeddingState::pending, "Ana (licensing)"},
      on_second));
  const OwnerRecord stranger{"own_2", "Other", "2026-01-01T00:00:00Z"};
  store->insert_owner(stranger, "hash-2");
  ModelRecord theirs = test::preparing_model("mdl_3", stranger.id);
  JobRecord their_prepare = test::job_record("job_7", stranger.id, "mdl_3", JobKind::prepare);
  their_prepare.created_at = "2026-01-01T00:00:07Z";
  store->insert_model(theirs, their_prepare);

  const auto copies = store->owner_embeddings(owner.id);
  ASSERT_EQ(copies.size(), 2u);
  EXPECT_EQ(copies[0].copy.recipient, "shop");
  EXPECT_EQ(copies[0].model_name, "bunny");
  EXPECT_EQ(copies[1].copy.recipient, "museum");
  EXPECT_EQ(copies[1].model_name, "dragon");
  EXPECT_EQ(copies[0].copy.requested_by, "") << "not said";
  EXPECT_EQ(copies[1].copy.requested_by, "Ana (licensing)");
  EXPECT_EQ(store->embeddings("mdl_2").at(0).requested_by, "Ana (licensing)");
  EXPECT_TRUE(store->owner_embeddings(stranger.id).empty());

  store->insert_job(job("job_4", JobKind::detect));
  store->insert_job(job("job_3", JobKind::detect));
  std::vector<std::string> detections;
  for (const JobRecord& j : store->model_jobs(owner.id, "mdl_1", JobKind::detect)) detections.push_back(j.id);
  EXPECT_EQ(detections, (std::vector<std::string>{"job_3", "job_4"}));
  EXPECT_TRUE(store->model_jobs(stranger.id, "mdl_1", JobKind::detect).empty());
}

TEST_P(StoreContract, ApiKeysAreLookedUpByHashOnly) {
  EXPECT_FALSE(store->owner_by_key_hash("hash-2"));
  EXPECT_THROW(store->insert_owner({"own_2", "Other", "t"}, "hash-1"), std::runtime_error);  // keys are unique
}

INSTANTIATE_TEST_SUITE_P(Backends, StoreContract, ::testing::ValuesIn(test::store_backends()),
                         [](const auto& info) { return test::backend_name(info.param); });

}  // namespace
}  // namespace meshmark::server
