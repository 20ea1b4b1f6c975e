#include "server/store/postgres_schema.hpp"

#include "server/store/sql_schema.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace meshmark::server::postgres {

namespace {

const std::vector<const char*>& migrations() {
  static const std::vector<const char*> list = {kSqlTables, kSqlJobLeases, kSqlEmbeddingRequester};
  return list;
}

// An arbitrary constant: the lock every meshmarkd takes while it migrates.
constexpr long long kMigrationLock = 0x6d65736d61726b;  // "mesmark"

int found_version(sql::Session& s) {
  s.execute("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
  const auto rows = s.query("SELECT COALESCE(MAX(version), 0) FROM schema_version");
  return static_cast<int>(rows.at(0).integer(0));
}

}  // namespace

int latest_schema_version() { return static_cast<int>(migrations().size()); }

void migrate(sql::Session& s) {
  s.query("SELECT pg_advisory_lock(?)", {kMigrationLock});
  try {
    const int found = found_version(s);
    if (found > latest_schema_version())
      throw std::runtime_error("the database has schema version " + std::to_string(found) + ", newer than the " +
                               std::to_string(latest_schema_version()) + " this meshmark knows: use a newer meshmark");
    for (int version = found + 1; version <= latest_schema_version(); ++version) {
      s.execute("BEGIN");
      s.execute(migrations()[static_cast<std::size_t>(version - 1)]);
      s.execute("INSERT INTO schema_version (version) VALUES (?)", {static_cast<long long>(version)});
      s.execute("COMMIT");
    }
  } catch (...) {
    try {
      s.execute("ROLLBACK");
      s.query("SELECT pg_advisory_unlock(?)", {kMigrationLock});
    } catch (const std::exception&) {  // the connection is gone, and its lock with it
    }
    throw;
  }
  s.query("SELECT pg_advisory_unlock(?)", {kMigrationLock});
}

}  // namespace meshmark::server::postgres
