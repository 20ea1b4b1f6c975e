#include "server/store/sqlite_store.hpp"

#include <gtest/gtest.h>

#include <set>

#include "tests/server/daemon_process.hpp"

namespace meshmark::server {
namespace {

struct Fixture {
  std::filesystem::path dir = test::temp_dir("store");
  OwnerRecord owner{"own_1", "Studio", "2026-01-01T00:00:00Z"};
  ModelRecord model() const {
    ModelRecord m;
    m.id = "mdl_1";
    m.owner_id = owner.id;
    m.name = "bunny";
    m.format = "obj";
    m.state = ModelState::preparing;
    m.report = {{"valid", true}};
    m.created_at = m.updated_at = "2026-01-01T00:00:00Z";
    return m;
  }
  JobRecord job(const std::string& id, JobKind kind) const {
    JobRecord j;
    j.id = id;
    j.owner_id = owner.id;
    j.model_id = "mdl_1";
    j.kind = kind;
    j.created_at = "2026-01-01T00:00:0" + id.substr(id.size() - 1) + "Z";
    return j;
  }
  EmbeddingRecord embedding(const std::string& id, const std::string& payload, const std::string& job_id) const {
    return {id, "mdl_1", owner.id, payload, "shop", job_id, {{"scheme", "spread"}}, "2026-01-01T00:00:00Z"};
  }
};

TEST(SqliteStore, RecordsSurviveReopening) {
  Fixture f;
  {
    SqliteStore store(f.dir / "db");
    store.insert_owner(f.owner, "hash-1");
    store.insert_model(f.model(), f.job("job_1", JobKind::prepare));
    ASSERT_TRUE(store.insert_embedding(f.embedding("emb_1", "ab", "job_2"), f.job("job_2", JobKind::embed)));
  }
  SqliteStore store(f.dir / "db");
  ASSERT_TRUE(store.owner_by_key_hash("hash-1"));
  EXPECT_EQ(store.owner_by_key_hash("hash-1")->name, "Studio");
  ASSERT_TRUE(store.model(f.owner.id, "mdl_1"));
  EXPECT_EQ(store.model(f.owner.id, "mdl_1")->report.value("valid", false), true);
  EXPECT_EQ(store.embeddings("mdl_1").size(), 1u);
  EXPECT_EQ(store.jobs_in_state(JobState::queued).size(), 2u);
}

TEST(SqliteStore, AnotherOwnerFindsNothing) {
  Fixture f;
  SqliteStore store(f.dir / "db");
  store.insert_owner(f.owner, "hash-1");
  store.insert_model(f.model(), f.job("job_1", JobKind::prepare));
  EXPECT_FALSE(store.model("own_2", "mdl_1"));
  EXPECT_FALSE(store.job("own_2", "job_1"));
  EXPECT_TRUE(store.models("own_2").empty());
  EXPECT_FALSE(store.delete_model("own_2", "mdl_1"));
  EXPECT_TRUE(store.model(f.owner.id, "mdl_1"));
}

TEST(SqliteStore, ADuplicatePayloadStoresNeitherTheEmbeddingNorItsJob) {
  Fixture f;
  SqliteStore store(f.dir / "db");
  store.insert_owner(f.owner, "hash-1");
  store.insert_model(f.model(), f.job("job_1", JobKind::prepare));
  ASSERT_TRUE(store.insert_embedding(f.embedding("emb_1", "ab", "job_2"), f.job("job_2", JobKind::embed)));
  EXPECT_FALSE(store.insert_embedding(f.embedding("emb_2", "ab", "job_3"), f.job("job_3", JobKind::embed)));
  EXPECT_EQ(store.embeddings("mdl_1").size(), 1u);
  EXPECT_FALSE(store.job_by_id("job_3"));
}

TEST(SqliteStore, DeletingAModelRemovesItsEmbeddingsAndAllItsJobsAndNamesThem) {
  Fixture f;
  SqliteStore store(f.dir / "db");
  store.insert_owner(f.owner, "hash-1");
  JobRecord prepare = f.job("job_1", JobKind::prepare);
  store.insert_model(f.model(), prepare);
  prepare.state = JobState::succeeded;
  store.update_job(prepare);
  ASSERT_TRUE(
      store.insert_embedding(f.embedding("emb_1", "ab", "job_2"), f.job("job_2", JobKind::embed)));  // still queued
  const auto jobs = store.delete_model(f.owner.id, "mdl_1");
  ASSERT_TRUE(jobs);
  EXPECT_EQ(std::set<std::string>(jobs->begin(), jobs->end()), (std::set<std::string>{"job_1", "job_2"}));
  EXPECT_FALSE(store.model(f.owner.id, "mdl_1"));
  EXPECT_TRUE(store.embeddings("mdl_1").empty());
  EXPECT_FALSE(store.job_by_id("job_1"));
  EXPECT_FALSE(store.job_by_id("job_2"));
}

TEST(SqliteStore, AnEmbeddingNeverMadeIsForgottenAndFreesItsPayload) {
  Fixture f;
  SqliteStore store(f.dir / "db");
  store.insert_owner(f.owner, "hash-1");
  store.insert_model(f.model(), f.job("job_1", JobKind::prepare));
  ASSERT_TRUE(store.insert_embedding(f.embedding("emb_1", "ab", "job_2"), f.job("job_2", JobKind::embed)));
  EXPECT_EQ(store.embeddings("mdl_1").at(0).state, EmbeddingState::pending);
  store.finish_embedding("emb_1", false);
  EXPECT_TRUE(store.embeddings("mdl_1").empty());
  EXPECT_TRUE(store.insert_embedding(f.embedding("emb_2", "ab", "job_3"), f.job("job_3", JobKind::embed)));
  store.finish_embedding("emb_2", true);
  EXPECT_EQ(store.embeddings("mdl_1").at(0).state, EmbeddingState::ready);
}

TEST(SqliteStore, JobUpdatesAreReadBack) {
  Fixture f;
  SqliteStore store(f.dir / "db");
  store.insert_owner(f.owner, "hash-1");
  JobRecord job = f.job("job_1", JobKind::prepare);
  store.insert_model(f.model(), job);
  job.state = JobState::succeeded;
  job.progress = 1;
  job.result = {{"seconds", 1.5}};
  job.attempts = 2;
  store.update_job(job);
  const auto read = store.job(f.owner.id, "job_1");
  ASSERT_TRUE(read);
  EXPECT_EQ(read->state, JobState::succeeded);
  EXPECT_EQ(read->result.value("seconds", 0.0), 1.5);
  EXPECT_EQ(read->attempts, 2);
  EXPECT_EQ((store.job_counts()[{"prepare", "succeeded"}]), 1);
}

TEST(SqliteStore, ApiKeysAreLookedUpByHashOnly) {
  Fixture f;
  SqliteStore store(f.dir / "db");
  store.insert_owner(f.owner, "hash-1");
  EXPECT_FALSE(store.owner_by_key_hash("hash-2"));
  EXPECT_THROW(store.insert_owner({"own_2", "Other", "t"}, "hash-1"), std::runtime_error);  // keys are unique
}

}  // namespace
}  // namespace meshmark::server
