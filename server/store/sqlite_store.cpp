#include "server/store/sqlite_store.hpp"

#include <sqlite3.h>

#include <cerrno>
#include <stdexcept>

#include "proto/json_text.hpp"
#include "server/store/job_transitions.hpp"
#include "server/store/storage_error.hpp"

#include "server/clock.hpp"

namespace meshmark::server {

namespace {

const char* kSchema = R"sql(
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
  vertices INTEGER NOT NULL,
  faces INTEGER NOT NULL,
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
  progress REAL NOT NULL,
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
CREATE INDEX IF NOT EXISTS jobs_by_state ON jobs(state, created_at);
)sql";

// A failed call's error, as StorageError: `full` when the disk or quota is.
[[noreturn]] void fail(sqlite3* db, int rc, const std::string& what) {
  const int code = rc & 0xff;
  const int os_error = sqlite3_system_errno(db);
  const bool full = code == SQLITE_FULL || os_error == ENOSPC || os_error == EDQUOT;
  throw StorageError("database: " + what + ": " + sqlite3_errmsg(db), full);
}

// A prepared statement, reset and finalized by RAII.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql) : db_(db) {
    if (const int rc = sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr); rc != SQLITE_OK)
      fail(db, rc, "cannot prepare a statement");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int i, const std::string& v) {
    sqlite3_bind_text(stmt_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& bind(int i, long long v) {
    sqlite3_bind_int64(stmt_, i, v);
    return *this;
  }
  Statement& bind(int i, double v) {
    sqlite3_bind_double(stmt_, i, v);
    return *this;
  }
  /// True while a row is available.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    fail(db_, rc, "a query failed");
  }
  /// Runs to completion; false on a constraint violation (e.g. a duplicate key).
  bool run() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_DONE) return true;
    if ((rc & 0xff) == SQLITE_CONSTRAINT) return false;
    fail(db_, rc, "a write failed");
  }
  std::string text(int col) const {
    const auto* p = sqlite3_column_text(stmt_, col);
    return p ? std::string(reinterpret_cast<const char*>(p), static_cast<std::size_t>(sqlite3_column_bytes(stmt_, col)))
             : "";
  }
  long long integer(int col) const { return sqlite3_column_int64(stmt_, col); }
  double real(int col) const { return sqlite3_column_double(stmt_, col); }
  bool is_null(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

void exec(sqlite3* db, const char* sql) {
  if (const int rc = sqlite3_exec(db, sql, nullptr, nullptr, nullptr); rc != SQLITE_OK) fail(db, rc, sql);
}

// BEGIN IMMEDIATE … COMMIT; rolls back unless commit() was reached (an error or an early return).
class Transaction {
 public:
  explicit Transaction(sqlite3* db) : db_(db) { exec(db_, "BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!committed_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit() {
    exec(db_, "COMMIT");
    committed_ = true;
  }

 private:
  sqlite3* db_;
  bool committed_ = false;
};

nlohmann::json parse_json(const std::string& text) {
  return text.empty() ? nlohmann::json() : nlohmann::json::parse(text, nullptr, false);
}

// A word read back from the store: one this version does not know means the database was
// written by another program (or a newer meshmark), which must not be guessed around.
template <typename Enum>
Enum stored_word(std::optional<Enum> parsed, const char* what, const std::string& text) {
  if (!parsed) throw std::runtime_error(std::string("the store holds an unknown ") + what + " '" + text + "'");
  return *parsed;
}

const char* kModelColumns =
    "id, owner_id, name, format, state, error, report, vertices, faces, digest, created_at, updated_at";

ModelRecord read_model(const Statement& s) {
  ModelRecord m;
  m.id = s.text(0);
  m.owner_id = s.text(1);
  m.name = s.text(2);
  m.format = s.text(3);
  m.state = stored_word(parse_model_state(s.text(4)), "model state", s.text(4));
  m.error = s.text(5);
  m.report = parse_json(s.text(6));
  m.vertices = s.integer(7);
  m.faces = s.integer(8);
  m.digest = s.text(9);
  m.created_at = s.text(10);
  m.updated_at = s.text(11);
  return m;
}

const char* kJobColumns =
    "id, owner_id, model_id, kind, state, progress, stage, request, result, error, attempts, created_at, started_at, "
    "finished_at, cancel_requested";

JobRecord read_job(const Statement& s) {
  JobRecord j;
  j.id = s.text(0);
  j.owner_id = s.text(1);
  j.model_id = s.text(2);
  j.kind = stored_word(parse_job_kind(s.text(3)), "job kind", s.text(3));
  j.state = stored_word(parse_job_state(s.text(4)), "job state", s.text(4));
  j.progress = s.real(5);
  j.stage = s.text(6);
  j.request = parse_json(s.text(7));
  j.result = s.is_null(8) ? nlohmann::json() : parse_json(s.text(8));
  j.error = s.text(9);
  j.attempts = static_cast<int>(s.integer(10));
  j.created_at = s.text(11);
  j.started_at = s.text(12);
  j.finished_at = s.text(13);
  j.cancel_requested = s.integer(14) != 0;
  return j;
}

}  // namespace

SqliteStore::SqliteStore(const std::filesystem::path& file) {
  if (sqlite3_open_v2(file.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK) {
    const std::string error = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw std::runtime_error("cannot open the database " + file.string() + ": " + error);
  }
  sqlite3_busy_timeout(db_, 5000);
  exec(db_, "PRAGMA journal_mode=WAL; PRAGMA synchronous=FULL; PRAGMA foreign_keys=ON;");
  exec(db_, kSchema);
  add_missing_columns();
}

// Databases made before a column existed get it, with its default.
void SqliteStore::add_missing_columns() {
  const auto has_column = [&](const char* table, const std::string& column) {
    Statement columns(db_, (std::string("PRAGMA table_info(") + table + ")").c_str());
    while (columns.step())
      if (columns.text(1) == column) return true;
    return false;
  };
  if (!has_column("jobs", "cancel_requested"))
    exec(db_, "ALTER TABLE jobs ADD COLUMN cancel_requested INTEGER NOT NULL DEFAULT 0");
  // Copies recorded before copies had states were all made.
  if (!has_column("embeddings", "state"))
    exec(db_,
         ("ALTER TABLE embeddings ADD COLUMN state TEXT NOT NULL DEFAULT '" + to_string(EmbeddingState::ready) + "'")
             .c_str());
}

SqliteStore::~SqliteStore() { sqlite3_close(db_); }

void SqliteStore::insert_owner(const OwnerRecord& owner, const std::string& api_key_hash) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "INSERT INTO owners (id, name, api_key_hash, created_at) VALUES (?, ?, ?, ?)");
  if (!s.bind(1, owner.id).bind(2, owner.name).bind(3, api_key_hash).bind(4, owner.created_at).run())
    throw std::runtime_error("database: an owner with this id or key exists");
}

std::optional<OwnerRecord> SqliteStore::owner_by_key_hash(const std::string& api_key_hash) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT id, name, created_at FROM owners WHERE api_key_hash = ?");
  s.bind(1, api_key_hash);
  if (!s.step()) return std::nullopt;
  return OwnerRecord{s.text(0), s.text(1), s.text(2), true};
}

std::vector<OwnerRecord> SqliteStore::owners() {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT id, name, created_at, api_key_hash FROM owners ORDER BY created_at, id");
  std::vector<OwnerRecord> out;
  while (s.step()) out.push_back(OwnerRecord{s.text(0), s.text(1), s.text(2), !s.text(3).starts_with("revoked:")});
  return out;
}

bool SqliteStore::set_api_key(const std::string& owner_id, const std::string& api_key_hash) {
  std::lock_guard lock(mutex_);
  // A revoked key is a value no key hashes to (hashes are hex), unique per owner.
  const std::string stored = api_key_hash.empty() ? "revoked:" + owner_id : api_key_hash;
  Statement s(db_, "UPDATE owners SET api_key_hash = ? WHERE id = ?");
  s.bind(1, stored).bind(2, owner_id);
  if (!s.run()) throw std::runtime_error("database: could not change the owner's key");
  return sqlite3_changes(db_) > 0;
}

void SqliteStore::insert_model(const ModelRecord& m, const JobRecord& prepare_job) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  Statement s(db_,
              "INSERT INTO models (id, owner_id, name, format, state, error, report, vertices, faces, digest, "
              "created_at, updated_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  s.bind(1, m.id).bind(2, m.owner_id).bind(3, m.name).bind(4, m.format).bind(5, to_string(m.state)).bind(6, m.error);
  s.bind(7, json_text(m.report)).bind(8, m.vertices).bind(9, m.faces).bind(10, m.digest).bind(11, m.created_at);
  s.bind(12, m.updated_at);
  if (!s.run()) throw std::runtime_error("database: a model with this id exists");
  insert_job_locked(prepare_job);
  transaction.commit();
}

std::optional<ModelRecord> SqliteStore::model(const std::string& owner_id, const std::string& model_id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, (std::string("SELECT ") + kModelColumns + " FROM models WHERE id = ? AND owner_id = ?").c_str());
  s.bind(1, model_id).bind(2, owner_id);
  if (!s.step()) return std::nullopt;
  return read_model(s);
}

std::optional<ModelRecord> SqliteStore::model_by_id(const std::string& model_id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, (std::string("SELECT ") + kModelColumns + " FROM models WHERE id = ?").c_str());
  s.bind(1, model_id);
  if (!s.step()) return std::nullopt;
  return read_model(s);
}

std::vector<ModelRecord> SqliteStore::models(const std::string& owner_id) {
  std::lock_guard lock(mutex_);
  Statement s(
      db_,
      (std::string("SELECT ") + kModelColumns + " FROM models WHERE owner_id = ? ORDER BY created_at, id").c_str());
  s.bind(1, owner_id);
  std::vector<ModelRecord> out;
  while (s.step()) out.push_back(read_model(s));
  return out;
}

void SqliteStore::set_model_state(const std::string& model_id, ModelState state, const std::string& error) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "UPDATE models SET state = ?, error = ?, updated_at = ? WHERE id = ?");
  s.bind(1, to_string(state)).bind(2, error).bind(3, now_iso8601()).bind(4, model_id).run();
}

void SqliteStore::set_model_payload_capacity(const std::string& model_id, int bits) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  nlohmann::json report;
  {
    Statement read(db_, "SELECT report FROM models WHERE id = ?");
    read.bind(1, model_id);
    if (!read.step()) return;  // deleted meanwhile
    report = parse_json(read.text(0));
  }
  if (!report.is_object()) report = nlohmann::json::object();
  report["robust_payload_bits"] = bits;
  Statement write(db_, "UPDATE models SET report = ? WHERE id = ?");
  write.bind(1, json_text(report)).bind(2, model_id).run();
  transaction.commit();
}

std::optional<std::vector<std::string>> SqliteStore::delete_model(const std::string& owner_id,
                                                                  const std::string& model_id) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  Statement model(db_, "SELECT 1 FROM models WHERE id = ? AND owner_id = ?");
  model.bind(1, model_id).bind(2, owner_id);
  if (!model.step()) return std::nullopt;
  std::vector<std::string> jobs;
  Statement listed(db_, "SELECT id FROM jobs WHERE model_id = ? AND owner_id = ?");
  listed.bind(1, model_id).bind(2, owner_id);
  while (listed.step()) jobs.push_back(listed.text(0));
  Statement remove_jobs(db_, "DELETE FROM jobs WHERE model_id = ? AND owner_id = ?");
  remove_jobs.bind(1, model_id).bind(2, owner_id).run();
  Statement remove_model(db_, "DELETE FROM models WHERE id = ? AND owner_id = ?");  // embeddings cascade
  remove_model.bind(1, model_id).bind(2, owner_id).run();
  transaction.commit();
  return jobs;
}

bool SqliteStore::insert_embedding(const EmbeddingRecord& e, const JobRecord& embed_job) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  Statement s(db_,
              "INSERT INTO embeddings (id, model_id, owner_id, payload, recipient, job_id, parameters, created_at, "
              "state) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)");
  s.bind(1, e.id).bind(2, e.model_id).bind(3, e.owner_id).bind(4, e.payload).bind(5, e.recipient).bind(6, e.job_id);
  s.bind(7, json_text(e.parameters)).bind(8, e.created_at).bind(9, to_string(e.state));
  if (!s.run()) return false;  // the transaction rolls back
  insert_job_locked(embed_job);
  transaction.commit();
  return true;
}

std::vector<EmbeddingRecord> SqliteStore::embeddings(const std::string& model_id) {
  std::lock_guard lock(mutex_);
  Statement s(db_,
              "SELECT id, model_id, owner_id, payload, recipient, job_id, parameters, created_at, state "
              "FROM embeddings WHERE model_id = ? ORDER BY created_at, id");
  s.bind(1, model_id);
  std::vector<EmbeddingRecord> out;
  while (s.step())
    out.push_back({s.text(0), s.text(1), s.text(2), s.text(3), s.text(4), s.text(5), parse_json(s.text(6)), s.text(7),
                   stored_word(parse_embedding_state(s.text(8)), "copy state", s.text(8))});
  return out;
}

void SqliteStore::finish_embedding(const std::string& embedding_id, bool made) {
  std::lock_guard lock(mutex_);
  // A copy that was never made was never handed out: its record goes, and its payload is free.
  if (made) {
    Statement s(db_, "UPDATE embeddings SET state = ? WHERE id = ?");
    s.bind(1, to_string(EmbeddingState::ready)).bind(2, embedding_id).run();
  } else {
    Statement s(db_, "DELETE FROM embeddings WHERE id = ?");
    s.bind(1, embedding_id).run();
  }
}

void SqliteStore::insert_job(const JobRecord& j) {
  std::lock_guard lock(mutex_);
  insert_job_locked(j);
}

void SqliteStore::insert_job_locked(const JobRecord& j) {
  Statement s(db_,
              "INSERT INTO jobs (id, owner_id, model_id, kind, state, progress, stage, request, result, error, "
              "attempts, created_at, started_at, finished_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, NULL, ?, ?, ?, ?, ?)");
  s.bind(1, j.id)
      .bind(2, j.owner_id)
      .bind(3, j.model_id)
      .bind(4, to_string(j.kind))
      .bind(5, to_string(j.state))
      .bind(6, j.progress);
  s.bind(7, j.stage).bind(8, json_text(j.request)).bind(9, j.error).bind(10, static_cast<long long>(j.attempts));
  s.bind(11, j.created_at).bind(12, j.started_at).bind(13, j.finished_at);
  if (!s.run()) throw std::runtime_error("database: a job with this id exists");
}

std::optional<JobRecord> SqliteStore::job(const std::string& owner_id, const std::string& job_id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, (std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ? AND owner_id = ?").c_str());
  s.bind(1, job_id).bind(2, owner_id);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

std::optional<JobRecord> SqliteStore::job_by_id(const std::string& job_id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, (std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ?").c_str());
  s.bind(1, job_id);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

void SqliteStore::update_job(const JobRecord& j) {
  std::lock_guard lock(mutex_);
  Statement s(db_,
              "UPDATE jobs SET state = ?, progress = ?, stage = ?, result = ?, error = ?, attempts = ?, "
              "started_at = ?, finished_at = ? WHERE id = ?");
  s.bind(1, to_string(j.state))
      .bind(2, j.progress)
      .bind(3, j.stage)
      .bind(4, j.result.is_null() ? std::string() : json_text(j.result));
  s.bind(5, j.error).bind(6, static_cast<long long>(j.attempts)).bind(7, j.started_at).bind(8, j.finished_at);
  s.bind(9, j.id).run();
}

CancelOutcome SqliteStore::cancel_job(const std::string& owner_id, const std::string& job_id, const std::string& now) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  // A queued job is canceled at once (a prepare takes its model with it); a running one is
  // asked to stop, durably, so that a restart does not run it again.
  // The same end as cancel_job() and model_outcome() (job_transitions.hpp) give, in one statement.
  JobRecord canceled;
  canceled.kind = JobKind::prepare;
  server::cancel_job(canceled, now);
  const ModelOutcome model_after = model_outcome(canceled);
  Statement queued(db_,
                   "UPDATE jobs SET state = ?, error = ?, stage = ?, finished_at = ? "
                   "WHERE id = ? AND owner_id = ? AND state = ?");
  queued.bind(1, to_string(canceled.state)).bind(2, canceled.error).bind(3, to_string(canceled.state)).bind(4, now);
  queued.bind(5, job_id).bind(6, owner_id).bind(7, to_string(JobState::queued)).run();
  if (sqlite3_changes(db_) > 0) {
    Statement model(db_,
                    "UPDATE models SET state = ?, error = ?, updated_at = ? "
                    "WHERE id = (SELECT model_id FROM jobs WHERE id = ? AND kind = ?)");
    model.bind(1, to_string(model_after.state)).bind(2, model_after.error).bind(3, now).bind(4, job_id);
    model.bind(5, to_string(JobKind::prepare)).run();
    transaction.commit();
    return CancelOutcome::canceled;
  }
  Statement running(db_, "UPDATE jobs SET cancel_requested = 1 WHERE id = ? AND owner_id = ? AND state = ?");
  running.bind(1, job_id).bind(2, owner_id).bind(3, to_string(JobState::running)).run();
  const bool requested = sqlite3_changes(db_) > 0;
  transaction.commit();
  if (requested) return CancelOutcome::requested;
  Statement exists(db_, "SELECT 1 FROM jobs WHERE id = ? AND owner_id = ?");
  exists.bind(1, job_id).bind(2, owner_id);
  return exists.step() ? CancelOutcome::finished : CancelOutcome::not_found;
}

std::vector<JobRecord> SqliteStore::jobs_in_state(JobState state) {
  std::lock_guard lock(mutex_);
  Statement s(db_,
              (std::string("SELECT ") + kJobColumns + " FROM jobs WHERE state = ? ORDER BY created_at, id").c_str());
  s.bind(1, to_string(state));
  std::vector<JobRecord> out;
  while (s.step()) out.push_back(read_job(s));
  return out;
}

std::map<std::pair<std::string, std::string>, long long> SqliteStore::job_counts() {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT kind, state, COUNT(*) FROM jobs GROUP BY kind, state");
  std::map<std::pair<std::string, std::string>, long long> out;
  while (s.step()) out[{s.text(0), s.text(1)}] = s.integer(2);
  return out;
}

bool SqliteStore::healthy() {
  std::lock_guard lock(mutex_);
  try {
    Statement s(db_, "SELECT 1");
    return s.step();
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace meshmark::server
