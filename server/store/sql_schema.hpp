#pragma once
// The tables both engines keep (SQLite reads BIGINT and DOUBLE PRECISION as its INTEGER and REAL),
// so that one SqlStore reads either. Each engine's migrations (sqlite_schema.cpp,
// postgres_schema.cpp) create them; unfinished jobs have a partial index, so the rows a
// recovery or a claim looks at stay few however many finished jobs the table holds.

namespace meshmark::server {

inline constexpr const char* kSqlTables = R"sql(
CREATE TABLE IF NOT EXISTS owners (
  id TEXT PRIMARY KEY,
  name TEXT NOT NULL,
  api_key_hash TEXT NOT NULL UNIQUE,
  created_at TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS models (
  id TEXT PRIMARY KEY,
  owner_id TEXT NOT NULL REFERENCES owners(id),
  name TEXT NOT NULL,
  format TEXT NOT NULL,
  state TEXT NOT NULL,
  error TEXT NOT NULL DEFAULT '',
  report TEXT NOT NULL,
  vertices BIGINT NOT NULL,
  faces BIGINT NOT NULL,
  digest TEXT NOT NULL,
  created_at TEXT NOT NULL,
  updated_at TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS models_by_owner ON models(owner_id);
CREATE TABLE IF NOT EXISTS embeddings (
  id TEXT PRIMARY KEY,
  model_id TEXT NOT NULL REFERENCES models(id) ON DELETE CASCADE,
  owner_id TEXT NOT NULL,
  payload TEXT NOT NULL,
  recipient TEXT NOT NULL DEFAULT '',
  job_id TEXT NOT NULL,
  parameters TEXT NOT NULL,
  created_at TEXT NOT NULL,
  state TEXT NOT NULL,
  UNIQUE (model_id, payload)
);
CREATE TABLE IF NOT EXISTS jobs (
  id TEXT PRIMARY KEY,
  owner_id TEXT NOT NULL,
  model_id TEXT NOT NULL,
  kind TEXT NOT NULL,
  state TEXT NOT NULL,
  progress DOUBLE PRECISION NOT NULL,
  stage TEXT NOT NULL,
  request TEXT NOT NULL,
  result TEXT,
  error TEXT NOT NULL DEFAULT '',
  attempts INTEGER NOT NULL DEFAULT 0,
  created_at TEXT NOT NULL,
  started_at TEXT NOT NULL DEFAULT '',
  finished_at TEXT NOT NULL DEFAULT '',
  cancel_requested INTEGER NOT NULL DEFAULT 0
);
CREATE INDEX IF NOT EXISTS jobs_by_model ON jobs(model_id);
CREATE INDEX IF NOT EXISTS jobs_by_state ON jobs(state, created_at);
CREATE INDEX IF NOT EXISTS jobs_unfinished ON jobs(state, created_at) WHERE state IN ('queued', 'running');
CREATE TABLE IF NOT EXISTS settings (key TEXT PRIMARY KEY, value TEXT NOT NULL);
)sql";

/// Jobs held by a daemon under a renewed lease (added after kSqlTables, by each engine's migration).
inline constexpr const char* kSqlJobLeases =
    "ALTER TABLE jobs ADD COLUMN lease_owner TEXT NOT NULL DEFAULT '';"
    "ALTER TABLE jobs ADD COLUMN lease_until TEXT NOT NULL DEFAULT '';";

/// Who asked for each copy (a label the caller gives; copies recorded before it say nothing).
inline constexpr const char* kSqlEmbeddingRequester =
    "ALTER TABLE embeddings ADD COLUMN requested_by TEXT NOT NULL DEFAULT '';";

}  // namespace meshmark::server
