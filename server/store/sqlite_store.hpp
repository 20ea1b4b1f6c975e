#pragma once
// The embedded store: the records (sql_store.hpp) in one SQLite file (sqlite_database.hpp).

#include <filesystem>

#include "server/store/sql_store.hpp"

namespace meshmark::server {

class SqliteStore : public SqlStore {
 public:
  /// Opens (creating if needed) the database file and brings its schema up to date
  /// (sqlite_schema.hpp). Throws StorageError, or std::runtime_error for a newer schema.
  explicit SqliteStore(const std::filesystem::path& file, const Clock& clock = system_clock());
};

}  // namespace meshmark::server
