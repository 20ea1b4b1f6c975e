#include "server/store/sql_store.hpp"

#include <stdexcept>

#include "proto/json_text.hpp"
#include "server/store/job_transitions.hpp"

namespace meshmark::server {

using sql::Params;
using sql::Row;
using sql::Session;

namespace {

// What daemons sharing the store hear when a job may have become claimable.
constexpr const char* kClaimableJobsChannel = "meshmark_claimable_jobs";

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

const std::string kModelColumns =
    "id, owner_id, name, format, state, error, report, vertices, faces, digest, created_at, updated_at";

ModelRecord read_model(const Row& s) {
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

const std::string kJobColumns =
    "id, owner_id, model_id, kind, state, progress, stage, request, result, error, attempts, created_at, started_at, "
    "finished_at, cancel_requested, lease_owner, lease_until";

JobRecord read_job(const Row& s) {
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
  j.lease_owner = s.text(15);
  j.lease_until = s.text(16);
  return j;
}

const std::string kEmbeddingColumns =
    "e.id, e.model_id, e.owner_id, e.payload, e.recipient, e.job_id, e.parameters, e.created_at, e.state, "
    "e.requested_by";
constexpr int kEmbeddingColumnCount = 10;

EmbeddingRecord read_embedding(const Row& r) {
  return {r.text(0),
          r.text(1),
          r.text(2),
          r.text(3),
          r.text(4),
          r.text(5),
          parse_json(r.text(6)),
          r.text(7),
          stored_word(parse_embedding_state(r.text(8)), "copy state", r.text(8)),
          r.text(9)};
}

template <typename Record>
std::optional<Record> first(const sql::Rows& rows, Record (*read)(const Row&)) {
  if (rows.empty()) return std::nullopt;
  return read(rows.front());
}

template <typename Record>
std::vector<Record> all(const sql::Rows& rows, Record (*read)(const Row&)) {
  std::vector<Record> out;
  out.reserve(rows.size());
  for (const Row& r : rows) out.push_back(read(r));
  return out;
}

const std::string kUnfinished = "('" + to_string(JobState::queued) + "', '" + to_string(JobState::running) + "')";

long long attempts_of(const JobRecord& j) { return j.attempts; }

void insert_job_in(Session& s, const JobRecord& j) {
  const auto inserted = s.execute(
      "INSERT INTO jobs (id, owner_id, model_id, kind, state, progress, stage, request, result, error, attempts, "
      "created_at, started_at, finished_at, cancel_requested, lease_owner, lease_until) "
      "VALUES (?, ?, ?, ?, ?, ?, ?, ?, NULL, ?, ?, ?, ?, ?, 0, ?, ?)",
      {j.id, j.owner_id, j.model_id, to_string(j.kind()), to_string(j.state), j.progress, j.stage,
       json_text(job_spec_json(j.spec)), j.error, attempts_of(j), j.created_at, j.started_at, j.finished_at,
       j.lease_owner, j.lease_until});
  if (!inserted) throw std::runtime_error("database: a job with this id exists");
}

JobWrite written_or_why(Session& s, long long changed, const std::string& job_id) {
  if (changed > 0) return JobWrite::written;
  return s.query("SELECT 1 FROM jobs WHERE id = ?", {job_id}).empty() ? JobWrite::gone : JobWrite::lost;
}

// The job's end and what follows from it, inside the caller's transaction.
JobWrite finish_job_in(Session& s, const JobRecord& j) {
  if (!j.finished()) throw std::logic_error("job " + j.id + " is not finished: " + to_string(j.state));
  const long long changed =
      s.execute(
           "UPDATE jobs SET state = ?, progress = ?, stage = ?, result = ?, error = ?, finished_at = ? "
           "WHERE id = ? AND attempts = ? AND state IN " +
               kUnfinished,
           {to_string(j.state), j.progress, j.stage,
            j.result.is_null() ? sql::Param(nullptr) : sql::Param(json_text(j.result)), j.error, j.finished_at, j.id,
            attempts_of(j)})
          .value_or(0);
  if (const JobWrite w = written_or_why(s, changed, j.id); w != JobWrite::written) return w;
  if (j.kind() == JobKind::prepare) {
    const ModelOutcome model = model_outcome(j);
    s.execute("UPDATE models SET state = ?, error = ?, updated_at = ? WHERE id = ?",
              {to_string(model.state), model.error, j.finished_at, j.model_id});
  }
  if (const auto* embed = std::get_if<EmbedJobSpec>(&j.spec)) {
    // A copy that was never made was never handed out: its record goes, and its payload is free.
    if (j.state == JobState::succeeded)
      s.execute("UPDATE embeddings SET state = ? WHERE id = ?",
                {to_string(EmbeddingState::ready), embed->embedding_id});
    else s.execute("DELETE FROM embeddings WHERE id = ?", {embed->embedding_id});
  }
  return JobWrite::written;
}

}  // namespace

SqlStore::SqlStore(std::unique_ptr<sql::Database> database, const Clock& clock)
    : database_(std::move(database)), clock_(clock) {}

void SqlStore::insert_owner(const OwnerRecord& owner, const std::string& api_key_hash) {
  database_->run([&](Session& s) {
    if (!s.execute("INSERT INTO owners (id, name, api_key_hash, created_at) VALUES (?, ?, ?, ?)",
                   {owner.id, owner.name, api_key_hash, owner.created_at}))
      throw std::runtime_error("database: an owner with this id or key exists");
  });
}

std::optional<OwnerRecord> SqlStore::owner_by_key_hash(const std::string& api_key_hash) {
  std::optional<OwnerRecord> owner;
  database_->run([&](Session& s) {
    const auto rows = s.query("SELECT id, name, created_at FROM owners WHERE api_key_hash = ?", {api_key_hash});
    if (!rows.empty()) owner = OwnerRecord{rows[0].text(0), rows[0].text(1), rows[0].text(2), true};
  });
  return owner;
}

std::vector<OwnerRecord> SqlStore::owners() {
  std::vector<OwnerRecord> out;
  database_->run([&](Session& s) {
    for (const Row& r : s.query("SELECT id, name, created_at, api_key_hash FROM owners ORDER BY created_at, id"))
      out.push_back(OwnerRecord{r.text(0), r.text(1), r.text(2), !r.text(3).starts_with("revoked:")});
  });
  return out;
}

bool SqlStore::set_api_key(const std::string& owner_id, const std::string& api_key_hash) {
  // A revoked key is a value no key hashes to (hashes are hex), unique per owner.
  const std::string stored = api_key_hash.empty() ? "revoked:" + owner_id : api_key_hash;
  std::optional<long long> changed;
  database_->run([&](Session& s) {
    changed = s.execute("UPDATE owners SET api_key_hash = ? WHERE id = ?", {stored, owner_id});
  });
  if (!changed) throw std::runtime_error("database: could not change the owner's key");
  return *changed > 0;
}

void SqlStore::insert_model(const ModelRecord& m, const JobRecord& prepare_job) {
  database_->transaction([&](Session& s) {
    if (!s.execute("INSERT INTO models (id, owner_id, name, format, state, error, report, vertices, faces, digest, "
                   "created_at, updated_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                   {m.id, m.owner_id, m.name, m.format, to_string(m.state), m.error, json_text(m.report), m.vertices,
                    m.faces, m.digest, m.created_at, m.updated_at}))
      throw std::runtime_error("database: a model with this id exists");
    insert_job_in(s, prepare_job);
    return true;
  });
}

std::optional<ModelRecord> SqlStore::model(const std::string& owner_id, const std::string& model_id) {
  std::optional<ModelRecord> out;
  database_->run([&](Session& s) {
    out = first(s.query("SELECT " + kModelColumns + " FROM models WHERE id = ? AND owner_id = ?", {model_id, owner_id}),
                read_model);
  });
  return out;
}

std::optional<ModelRecord> SqlStore::model_by_id(const std::string& model_id) {
  std::optional<ModelRecord> out;
  database_->run([&](Session& s) {
    out = first(s.query("SELECT " + kModelColumns + " FROM models WHERE id = ?", {model_id}), read_model);
  });
  return out;
}

std::vector<ModelRecord> SqlStore::models(const std::string& owner_id) {
  std::vector<ModelRecord> out;
  database_->run([&](Session& s) {
    out =
        all(s.query("SELECT " + kModelColumns + " FROM models WHERE owner_id = ? ORDER BY created_at, id", {owner_id}),
            read_model);
  });
  return out;
}

void SqlStore::set_model_payload_capacity(const std::string& model_id, int bits) {
  database_->transaction([&](Session& s) {
    const auto rows = s.query("SELECT report FROM models WHERE id = ?", {model_id});
    if (rows.empty()) return false;  // deleted meanwhile
    nlohmann::json report = parse_json(rows[0].text(0));
    if (!report.is_object()) report = nlohmann::json::object();
    report["robust_payload_bits"] = bits;
    s.execute("UPDATE models SET report = ? WHERE id = ?", {json_text(report), model_id});
    return true;
  });
}

std::optional<std::vector<std::string>> SqlStore::delete_model(const std::string& owner_id,
                                                               const std::string& model_id) {
  std::optional<std::vector<std::string>> jobs;
  database_->transaction([&](Session& s) {
    if (s.query("SELECT 1 FROM models WHERE id = ? AND owner_id = ?", {model_id, owner_id}).empty()) return false;
    jobs.emplace();
    for (const Row& r : s.query("SELECT id FROM jobs WHERE model_id = ? AND owner_id = ?", {model_id, owner_id}))
      jobs->push_back(r.text(0));
    s.execute("DELETE FROM jobs WHERE model_id = ? AND owner_id = ?", {model_id, owner_id});
    s.execute("DELETE FROM models WHERE id = ? AND owner_id = ?", {model_id, owner_id});  // embeddings cascade
    return true;
  });
  return jobs;
}

bool SqlStore::insert_embedding(const EmbeddingRecord& e, const JobRecord& embed_job) {
  bool stored = false;
  database_->transaction([&](Session& s) {
    stored = s.execute(
                  "INSERT INTO embeddings (id, model_id, owner_id, payload, recipient, job_id, parameters, "
                  "created_at, state, requested_by) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                  {e.id, e.model_id, e.owner_id, e.payload, e.recipient, e.job_id, json_text(e.parameters),
                   e.created_at, to_string(e.state), e.requested_by})
                 .has_value();
    if (stored) insert_job_in(s, embed_job);
    return stored;  // a duplicate payload stores neither
  });
  return stored;
}

std::vector<EmbeddingRecord> SqlStore::embeddings(const std::string& model_id) {
  std::vector<EmbeddingRecord> out;
  database_->run([&](Session& s) {
    out = all(
        s.query("SELECT " + kEmbeddingColumns + " FROM embeddings e WHERE e.model_id = ? ORDER BY e.created_at, e.id",
                {model_id}),
        read_embedding);
  });
  return out;
}

std::vector<HandedOutCopy> SqlStore::owner_embeddings(const std::string& owner_id) {
  std::vector<HandedOutCopy> out;
  database_->run([&](Session& s) {
    for (const Row& r : s.query("SELECT " + kEmbeddingColumns +
                                    ", m.name FROM embeddings e JOIN models m ON m.id = e.model_id "
                                    "WHERE m.owner_id = ? ORDER BY e.created_at, e.id",
                                {owner_id}))
      out.push_back({read_embedding(r), r.text(kEmbeddingColumnCount)});
  });
  return out;
}

std::vector<JobRecord> SqlStore::model_jobs(const std::string& owner_id, const std::string& model_id, JobKind kind) {
  std::vector<JobRecord> out;
  database_->run([&](Session& s) {
    out = all(s.query("SELECT " + kJobColumns +
                          " FROM jobs WHERE model_id = ? AND owner_id = ? AND kind = ? ORDER BY created_at, id",
                      {model_id, owner_id, to_string(kind)}),
              read_job);
  });
  return out;
}

void SqlStore::insert_job(const JobRecord& j) {
  database_->run([&](Session& s) { insert_job_in(s, j); });
}

std::optional<JobRecord> SqlStore::job(const std::string& owner_id, const std::string& job_id) {
  std::optional<JobRecord> out;
  database_->run([&](Session& s) {
    out = first(s.query("SELECT " + kJobColumns + " FROM jobs WHERE id = ? AND owner_id = ?", {job_id, owner_id}),
                read_job);
  });
  return out;
}

std::optional<JobRecord> SqlStore::job_by_id(const std::string& job_id) {
  std::optional<JobRecord> out;
  database_->run([&](Session& s) {
    out = first(s.query("SELECT " + kJobColumns + " FROM jobs WHERE id = ?", {job_id}), read_job);
  });
  return out;
}

JobWrite SqlStore::write_job(const std::string& statement, const Params& params, const std::string& job_id) {
  JobWrite outcome = JobWrite::lost;
  database_->run([&](Session& s) { outcome = written_or_why(s, s.execute(statement, params).value_or(0), job_id); });
  return outcome;
}

JobWrite SqlStore::start_job(const JobRecord& j) {
  return write_job(
      "UPDATE jobs SET state = ?, attempts = ?, started_at = ?, stage = ?, progress = ? "
      "WHERE id = ? AND attempts = ? AND lease_owner = ? AND state IN " +
          kUnfinished,
      {to_string(j.state), attempts_of(j), j.started_at, j.stage, j.progress, j.id, attempts_of(j) - 1, j.lease_owner},
      j.id);
}

JobWrite SqlStore::save_progress(const JobRecord& j) {
  return write_job(
      "UPDATE jobs SET stage = ?, progress = ? "
      "WHERE id = ? AND attempts = ? AND state = ? AND cancel_requested = 0",
      {j.stage, j.progress, j.id, attempts_of(j), to_string(JobState::running)}, j.id);
}

JobWrite SqlStore::requeue_job(const JobRecord& j) {
  return write_job("UPDATE jobs SET state = ?, stage = ? WHERE id = ? AND attempts = ? AND state = ?",
                   {to_string(j.state), j.stage, j.id, attempts_of(j), to_string(JobState::running)}, j.id);
}

JobWrite SqlStore::finish_job(const JobRecord& job) {
  JobWrite outcome = JobWrite::lost;
  database_->transaction([&](Session& s) {
    outcome = finish_job_in(s, job);
    return outcome == JobWrite::written;
  });
  return outcome;
}

void SqlStore::renew_leases(const std::string& owner, const std::string& until) {
  database_->run([&](Session& s) {
    s.execute("UPDATE jobs SET lease_until = ? WHERE lease_owner = ? AND state IN " + kUnfinished, {until, owner});
  });
}

std::vector<JobRecord> SqlStore::take_over_jobs(const std::string& owner, const std::string& now,
                                                const std::string& until, bool including_own) {
  std::vector<JobRecord> taken;
  database_->run([&](Session& s) {
    const auto candidates = all(s.query("SELECT " + kJobColumns + " FROM jobs WHERE state IN " + kUnfinished +
                                            " AND (lease_until < ? OR lease_owner = ?) ORDER BY created_at, id",
                                        {now, including_own ? owner : std::string("\n")}),  // no daemon is called "\n"
                                read_job);
    for (JobRecord job : candidates) {
      // Taken only if nobody took it since it was read: one taker wins.
      const auto changed = s.execute(
          "UPDATE jobs SET lease_owner = ?, lease_until = ? WHERE id = ? AND lease_owner = ? AND lease_until = ?",
          {owner, until, job.id, job.lease_owner, job.lease_until});
      if (changed.value_or(0) == 0) continue;
      job.lease_owner = owner;
      job.lease_until = until;
      taken.push_back(std::move(job));
    }
  });
  return taken;
}

std::optional<JobRecord> SqlStore::claim_queued_job(const std::string& owner, const std::string& until) {
  std::optional<JobRecord> claimed;
  database_->transaction([&](Session& s) {
    // A claimed job is marked so, until its claimer starts it: nobody else claims it meanwhile.
    const auto rows = s.query(
        "SELECT j.id FROM jobs j JOIN models m ON m.id = j.model_id WHERE j.state = ? AND j.lease_owner <> ? "
        "AND j.stage <> ? AND (j.kind = ? OR m.state <> ?) ORDER BY j.created_at, j.id LIMIT 1" +
            database_->skip_locked("j"),
        {to_string(JobState::queued), owner, std::string(kClaimedStage), to_string(JobKind::prepare),
         to_string(ModelState::preparing)});
    if (rows.empty()) return false;
    s.execute("UPDATE jobs SET lease_owner = ?, lease_until = ?, stage = ? WHERE id = ?",
              {owner, until, std::string(kClaimedStage), rows[0].text(0)});
    claimed = first(s.query("SELECT " + kJobColumns + " FROM jobs WHERE id = ?", {rows[0].text(0)}), read_job);
    return true;
  });
  return claimed;
}

void SqlStore::announce_claimable_jobs() {
  database_->run([&](Session& s) { database_->announce(s, kClaimableJobsChannel); });
}

std::unique_ptr<Subscription> SqlStore::watch_claimable_jobs(std::function<void()> wake) {
  return database_->listen(kClaimableJobsChannel, std::move(wake));
}

CancelOutcome SqlStore::cancel_job(const std::string& owner_id, const std::string& job_id) {
  CancelOutcome outcome = CancelOutcome::not_found;
  database_->transaction([&](Session& s) {
    auto job = first(s.query("SELECT " + kJobColumns + " FROM jobs WHERE id = ? AND owner_id = ?", {job_id, owner_id}),
                     read_job);
    if (!job) return false;
    if (job->state == JobState::queued) {  // ends now (a prepare takes its model with it)
      server::cancel_job(*job, clock_.now_iso8601());
      if (finish_job_in(s, *job) != JobWrite::written) throw std::logic_error("a queued job could not be canceled");
      outcome = CancelOutcome::canceled;
      return true;
    }
    outcome = CancelOutcome::finished;
    if (job->state != JobState::running) return false;
    // Recorded durably, so that a restart does not run it again.
    s.execute("UPDATE jobs SET cancel_requested = 1 WHERE id = ?", {job_id});
    outcome = CancelOutcome::requested;
    return true;
  });
  return outcome;
}

std::vector<JobRecord> SqlStore::jobs_in_state(JobState state) {
  std::vector<JobRecord> out;
  database_->run([&](Session& s) {
    out =
        all(s.query("SELECT " + kJobColumns + " FROM jobs WHERE state = ? ORDER BY created_at, id", {to_string(state)}),
            read_job);
  });
  return out;
}

std::map<std::pair<std::string, std::string>, long long> SqlStore::job_counts() {
  std::map<std::pair<std::string, std::string>, long long> out;
  database_->run([&](Session& s) {
    for (const Row& r : s.query("SELECT kind, state, COUNT(*) FROM jobs GROUP BY kind, state"))
      out[{r.text(0), r.text(1)}] = r.integer(2);
  });
  return out;
}

std::string SqlStore::record_master_key_fingerprint(const std::string& ours) {
  std::string fingerprint = ours;
  database_->transaction([&](Session& s) {
    s.execute("INSERT INTO settings (key, value) VALUES ('master_key_fingerprint', ?) ON CONFLICT (key) DO NOTHING",
              {ours});
    const auto rows = s.query("SELECT value FROM settings WHERE key = 'master_key_fingerprint'");
    if (!rows.empty()) fingerprint = rows[0].text(0);
    return true;
  });
  return fingerprint;
}

bool SqlStore::healthy() { return database_->healthy(); }

}  // namespace meshmark::server
