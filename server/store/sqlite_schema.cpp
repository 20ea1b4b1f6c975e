#include "server/store/sqlite_schema.hpp"

#include <sqlite3.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "proto/job_specs.hpp"
#include "proto/json_text.hpp"
#include "server/store/sql_schema.hpp"
#include "server/store/sqlite_db.hpp"

namespace meshmark::server::sqlite {

namespace {

bool has_column(sqlite3* db, const std::string& table, const std::string& column) {
  Statement columns(db, "PRAGMA table_info(" + table + ")");
  while (columns.step())
    if (columns.text(1) == column) return true;
  return false;
}

// 1: the tables. Databases made before versions were kept (version 0, tables present) lack the
// columns added since; they get them with their defaults.
void create_tables(sqlite3* db) {
  exec(db, kSqlTables);
  if (!has_column(db, "jobs", "cancel_requested"))
    exec(db, "ALTER TABLE jobs ADD COLUMN cancel_requested INTEGER NOT NULL DEFAULT 0");
  if (!has_column(db, "embeddings", "state"))  // copies recorded before copies had states were all made
    exec(db, "ALTER TABLE embeddings ADD COLUMN state TEXT NOT NULL DEFAULT 'ready'");
}

// 2: job requests become typed, versioned specs (proto/job_specs.hpp).
void version_job_specs(sqlite3* db) {
  std::vector<std::pair<std::string, std::string>> rewritten;
  {
    Statement jobs(db, "SELECT id, kind, request FROM jobs");
    while (jobs.step()) {
      const auto kind = parse_job_kind(jobs.text(1));
      const auto stored = nlohmann::json::parse(jobs.text(2), nullptr, false);
      if (!kind || stored.is_discarded()) continue;  // read_job refuses it, with its reason
      rewritten.emplace_back(jobs.text(0), json_text(upgrade_job_spec(*kind, stored)));
    }
  }
  for (const auto& [id, spec] : rewritten) {
    Statement update(db, "UPDATE jobs SET request = ? WHERE id = ?");
    update.bind(1, spec).bind(2, id).run();
  }
}

// 3: settings the daemons on one store must agree on (the master key's fingerprint); a database
// made since holds it from 1.
void create_settings(sqlite3* db) {
  exec(db, "CREATE TABLE IF NOT EXISTS settings (key TEXT PRIMARY KEY, value TEXT NOT NULL)");
}

// 4: jobs held under leases (sql_schema.hpp).
void add_job_leases(sqlite3* db) { exec(db, kSqlJobLeases); }

// 5: who asked for each copy.
void add_embedding_requester(sqlite3* db) { exec(db, kSqlEmbeddingRequester); }

const std::vector<std::function<void(sqlite3*)>>& migrations() {
  static const std::vector<std::function<void(sqlite3*)>> list = {create_tables, version_job_specs, create_settings,
                                                                  add_job_leases, add_embedding_requester};
  return list;
}

int user_version(sqlite3* db) {
  Statement s(db, "PRAGMA user_version");
  return s.step() ? static_cast<int>(s.integer(0)) : 0;
}

}  // namespace

int latest_schema_version() { return static_cast<int>(migrations().size()); }

void migrate(sqlite3* db) {
  const int found = user_version(db);
  if (found > latest_schema_version())
    throw std::runtime_error("the database has schema version " + std::to_string(found) + ", newer than the " +
                             std::to_string(latest_schema_version()) + " this meshmark knows: use a newer meshmark");
  for (int version = found + 1; version <= latest_schema_version(); ++version) {
    Transaction transaction(db);
    migrations()[static_cast<std::size_t>(version - 1)](db);
    exec(db, "PRAGMA user_version = " + std::to_string(version));
    transaction.commit();
  }
}

}  // namespace meshmark::server::sqlite
