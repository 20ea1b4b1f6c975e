#include "server/store/sqlite_store.hpp"

#include <sqlite3.h>

#include <stdexcept>

#include "proto/json_text.hpp"
#include "server/store/job_transitions.hpp"
#include "server/store/sqlite_db.hpp"
#include "server/store/sqlite_schema.hpp"

namespace meshmark::server {

using sqlite::Statement;
using sqlite::Transaction;

namespace {

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

JobSpec stored_spec(JobKind kind, const std::string& text) {
  try {
    return parse_job_spec(kind, parse_json(text));
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("the store holds a job spec this version cannot read: ") + e.what());
  }
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
  const JobKind kind = stored_word(parse_job_kind(s.text(3)), "job kind", s.text(3));
  j.state = stored_word(parse_job_state(s.text(4)), "job state", s.text(4));
  j.progress = s.real(5);
  j.stage = s.text(6);
  j.spec = stored_spec(kind, s.text(7));
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

SqliteStore::SqliteStore(const std::filesystem::path& file, const Clock& clock) : clock_(clock) {
  if (sqlite3_open_v2(file.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK) {
    const std::string error = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw std::runtime_error("cannot open the database " + file.string() + ": " + error);
  }
  try {
    sqlite3_busy_timeout(db_, 5000);
    sqlite::exec(db_, "PRAGMA journal_mode=WAL; PRAGMA synchronous=FULL; PRAGMA foreign_keys=ON;");
    sqlite::migrate(db_);
  } catch (...) {
    sqlite3_close(db_);
    throw;
  }
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
  return sqlite::changes(db_) > 0;
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
  Statement s(db_, std::string("SELECT ") + kModelColumns + " FROM models WHERE id = ? AND owner_id = ?");
  s.bind(1, model_id).bind(2, owner_id);
  if (!s.step()) return std::nullopt;
  return read_model(s);
}

std::optional<ModelRecord> SqliteStore::model_by_id(const std::string& model_id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kModelColumns + " FROM models WHERE id = ?");
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
      .bind(4, to_string(j.kind()))
      .bind(5, to_string(j.state))
      .bind(6, j.progress);
  s.bind(7, j.stage)
      .bind(8, json_text(job_spec_json(j.spec)))
      .bind(9, j.error)
      .bind(10, static_cast<long long>(j.attempts));
  s.bind(11, j.created_at).bind(12, j.started_at).bind(13, j.finished_at);
  if (!s.run()) throw std::runtime_error("database: a job with this id exists");
}

std::optional<JobRecord> SqliteStore::job(const std::string& owner_id, const std::string& job_id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ? AND owner_id = ?");
  s.bind(1, job_id).bind(2, owner_id);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

std::optional<JobRecord> SqliteStore::job_by_id(const std::string& job_id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ?");
  s.bind(1, job_id);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

namespace {

const std::string kUnfinished = "('" + to_string(JobState::queued) + "', '" + to_string(JobState::running) + "')";

}  // namespace

JobWrite SqliteStore::written_or_why(const std::string& job_id) {
  if (sqlite::changes(db_) > 0) return JobWrite::written;
  Statement exists(db_, "SELECT 1 FROM jobs WHERE id = ?");
  exists.bind(1, job_id);
  return exists.step() ? JobWrite::lost : JobWrite::gone;
}

JobWrite SqliteStore::start_job(const JobRecord& j) {
  std::lock_guard lock(mutex_);
  Statement s(db_,
              "UPDATE jobs SET state = ?, attempts = ?, started_at = ?, stage = ?, progress = ? "
              "WHERE id = ? AND attempts = ? AND state IN " +
                  kUnfinished);
  s.bind(1, to_string(j.state)).bind(2, static_cast<long long>(j.attempts)).bind(3, j.started_at).bind(4, j.stage);
  s.bind(5, j.progress).bind(6, j.id).bind(7, static_cast<long long>(j.attempts - 1)).run();
  return written_or_why(j.id);
}

JobWrite SqliteStore::save_progress(const JobRecord& j) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "UPDATE jobs SET stage = ?, progress = ? WHERE id = ? AND attempts = ? AND state = ?");
  s.bind(1, j.stage).bind(2, j.progress).bind(3, j.id).bind(4, static_cast<long long>(j.attempts));
  s.bind(5, to_string(JobState::running)).run();
  return written_or_why(j.id);
}

JobWrite SqliteStore::requeue_job(const JobRecord& j) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "UPDATE jobs SET state = ?, stage = ? WHERE id = ? AND attempts = ? AND state = ?");
  s.bind(1, to_string(j.state)).bind(2, j.stage).bind(3, j.id).bind(4, static_cast<long long>(j.attempts));
  s.bind(5, to_string(JobState::running)).run();
  return written_or_why(j.id);
}

JobWrite SqliteStore::finish_job(const JobRecord& job) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  const JobWrite outcome = finish_job_locked(job);
  if (outcome == JobWrite::written) transaction.commit();
  return outcome;
}

JobWrite SqliteStore::finish_job_locked(const JobRecord& j) {
  if (!j.finished()) throw std::logic_error("job " + j.id + " is not finished: " + to_string(j.state));
  Statement s(db_,
              "UPDATE jobs SET state = ?, progress = ?, stage = ?, result = ?, error = ?, finished_at = ? "
              "WHERE id = ? AND attempts = ? AND state IN " +
                  kUnfinished);
  s.bind(1, to_string(j.state)).bind(2, j.progress).bind(3, j.stage);
  s.bind(4, j.result.is_null() ? std::string() : json_text(j.result)).bind(5, j.error).bind(6, j.finished_at);
  s.bind(7, j.id).bind(8, static_cast<long long>(j.attempts)).run();
  if (const JobWrite w = written_or_why(j.id); w != JobWrite::written) return w;
  if (j.kind() == JobKind::prepare) {
    const ModelOutcome model = model_outcome(j);
    Statement m(db_, "UPDATE models SET state = ?, error = ?, updated_at = ? WHERE id = ?");
    m.bind(1, to_string(model.state)).bind(2, model.error).bind(3, j.finished_at).bind(4, j.model_id).run();
  }
  if (const auto* embed = std::get_if<EmbedJobSpec>(&j.spec)) {
    // A copy that was never made was never handed out: its record goes, and its payload is free.
    if (j.state == JobState::succeeded) {
      Statement e(db_, "UPDATE embeddings SET state = ? WHERE id = ?");
      e.bind(1, to_string(EmbeddingState::ready)).bind(2, embed->embedding_id).run();
    } else {
      Statement e(db_, "DELETE FROM embeddings WHERE id = ?");
      e.bind(1, embed->embedding_id).run();
    }
  }
  return JobWrite::written;
}

CancelOutcome SqliteStore::cancel_job(const std::string& owner_id, const std::string& job_id) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  std::optional<JobRecord> job;
  {
    Statement s(db_, std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ? AND owner_id = ?");
    s.bind(1, job_id).bind(2, owner_id);
    if (s.step()) job = read_job(s);
  }
  if (!job) return CancelOutcome::not_found;
  if (job->state == JobState::queued) {  // ends now (a prepare takes its model with it)
    server::cancel_job(*job, clock_.now_iso8601());
    if (finish_job_locked(*job) != JobWrite::written) throw std::logic_error("a queued job could not be canceled");
    transaction.commit();
    return CancelOutcome::canceled;
  }
  if (job->state != JobState::running) return CancelOutcome::finished;
  // Recorded durably, so that a restart does not run it again.
  Statement running(db_, "UPDATE jobs SET cancel_requested = 1 WHERE id = ?");
  running.bind(1, job_id).run();
  transaction.commit();
  return CancelOutcome::requested;
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

std::string SqliteStore::record_master_key_fingerprint(const std::string& ours) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  Statement insert(db_, "INSERT OR IGNORE INTO settings (key, value) VALUES ('master_key_fingerprint', ?)");
  insert.bind(1, ours).run();
  Statement stored(db_, "SELECT value FROM settings WHERE key = 'master_key_fingerprint'");
  const std::string fingerprint = stored.step() ? stored.text(0) : ours;
  transaction.commit();
  return fingerprint;
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
