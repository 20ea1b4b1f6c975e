#pragma once
// SQLite behind sql::Database: one file in WAL mode with synchronous=FULL and foreign keys on, its
// schema brought up to date at open (sqlite_schema.hpp). One connection behind a mutex: every
// statement is short, and SQLite serializes writers anyway.

#include <filesystem>
#include <mutex>

#include "server/store/sql_database.hpp"

struct sqlite3;

namespace meshmark::server {

class SqliteDatabase : public sql::Database {
 public:
  /// Throws StorageError, or std::runtime_error for a schema newer than this version's.
  explicit SqliteDatabase(const std::filesystem::path& file);
  ~SqliteDatabase() override;
  SqliteDatabase(const SqliteDatabase&) = delete;
  SqliteDatabase& operator=(const SqliteDatabase&) = delete;

  void transaction(const std::function<bool(sql::Session&)>& work) override;
  void run(const std::function<void(sql::Session&)>& work) override;
  bool healthy() override;
  std::string skip_locked(const std::string&) const override { return ""; }

 private:
  std::mutex mutex_;
  sqlite3* db_ = nullptr;
};

}  // namespace meshmark::server
