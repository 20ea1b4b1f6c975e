#include "server/store/sqlite_schema.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "server/store/sqlite_db.hpp"
#include "server/store/sqlite_store.hpp"
#include "tests/server/daemon_process.hpp"

namespace meshmark::server {
namespace {

// A database as the first daemons wrote it: no schema version, no cancel requests, copies without
// states, an embed job's request flat.
const char* kFirstSchema = R"sql(
CREATE TABLE owners (id TEXT PRIMARY KEY, name TEXT NOT NULL, api_key_hash TEXT NOT NULL UNIQUE,
  created_at TEXT NOT NULL);
CREATE TABLE models (id TEXT PRIMARY KEY, owner_id TEXT NOT NULL REFERENCES owners(id), name TEXT NOT NULL,
  format TEXT NOT NULL, state TEXT NOT NULL, error TEXT NOT NULL DEFAULT '', report TEXT NOT NULL,
  vertices INTEGER NOT NULL, faces INTEGER NOT NULL, digest TEXT NOT NULL, created_at TEXT NOT NULL,
  updated_at TEXT NOT NULL);
CREATE TABLE embeddings (id TEXT PRIMARY KEY, model_id TEXT NOT NULL REFERENCES models(id) ON DELETE CASCADE,
  owner_id TEXT NOT NULL, payload TEXT NOT NULL, recipient TEXT NOT NULL DEFAULT '', job_id TEXT NOT NULL,
  parameters TEXT NOT NULL, created_at TEXT NOT NULL, UNIQUE (model_id, payload));
CREATE TABLE jobs (id TEXT PRIMARY KEY, owner_id TEXT NOT NULL, model_id TEXT NOT NULL, kind TEXT NOT NULL,
  state TEXT NOT NULL, progress REAL NOT NULL, stage TEXT NOT NULL, request TEXT NOT NULL, result TEXT,
  error TEXT NOT NULL DEFAULT '', attempts INTEGER NOT NULL DEFAULT 0, created_at TEXT NOT NULL,
  started_at TEXT NOT NULL DEFAULT '', finished_at TEXT NOT NULL DEFAULT '');
INSERT INTO owners VALUES ('own_1', 'Studio', 'hash-1', 't');
INSERT INTO models VALUES ('mdl_1', 'own_1', 'bunny', 'ply', 'ready', '', '{}', 100, 196, 'd', 't', 't');
INSERT INTO embeddings VALUES ('emb_1', 'mdl_1', 'own_1', 'ab', 'shop', 'job_2', '{}', 't');
INSERT INTO jobs VALUES ('job_2', 'own_1', 'mdl_1', 'embed', 'queued', 0, 'queued',
  '{"recipient":"shop","embedding_id":"emb_1","output_format":"ply","assigned_payload":"ab"}', NULL, '', 0, 't', '', '');
)sql";

void write_database(const std::filesystem::path& file, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  sqlite::exec(db, sql);
  sqlite3_close(db);
}

int schema_version(const std::filesystem::path& file) {
  sqlite3* db = nullptr;
  sqlite3_open(file.c_str(), &db);
  int version = -1;
  {  // finalized before the close: a connection with a live statement is not closed (and leaks)
    sqlite::Statement s(db, "PRAGMA user_version");
    if (s.step()) version = static_cast<int>(s.integer(0));
  }
  sqlite3_close(db);
  return version;
}

TEST(SqliteSchema, TheFirstDaemonsDatabaseIsBroughtUpToDate) {
  const auto file = test::temp_dir("schema") / "meshmark.db";
  write_database(file, kFirstSchema);
  {
    SqliteStore store(file);
    const auto job = store.job_by_id("job_2");
    ASSERT_TRUE(job);
    const auto& spec = std::get<EmbedJobSpec>(job->spec);
    EXPECT_EQ(spec.request.recipient, "shop");
    EXPECT_EQ(spec.assigned_payload, "ab");
    EXPECT_FALSE(job->cancel_requested);
    EXPECT_EQ(store.embeddings("mdl_1").at(0).state, EmbeddingState::ready) << "copies before states were all made";
    EXPECT_EQ(store.embeddings("mdl_1").at(0).requested_by, "") << "who asked was not recorded then";
  }
  EXPECT_EQ(schema_version(file), sqlite::latest_schema_version());
  SqliteStore again(file);  // nothing left to migrate
  EXPECT_TRUE(again.job_by_id("job_2"));
}

TEST(SqliteSchema, ANewDatabaseHasTheLatestVersion) {
  const auto file = test::temp_dir("schema") / "meshmark.db";
  { SqliteStore store(file); }
  EXPECT_EQ(schema_version(file), sqlite::latest_schema_version());
}

TEST(SqliteSchema, ADatabaseFromANewerMeshmarkIsRefused) {
  const auto file = test::temp_dir("schema") / "meshmark.db";
  write_database(file, "PRAGMA user_version = " + std::to_string(sqlite::latest_schema_version() + 1));
  try {
    SqliteStore store(file);
    FAIL() << "opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("newer"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace meshmark::server
