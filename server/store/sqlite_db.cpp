#include "server/store/sqlite_db.hpp"

#include <sqlite3.h>

#include <cerrno>

#include "server/store/storage_error.hpp"

namespace meshmark::server::sqlite {

namespace {

StorageError::Kind kind_of(sqlite3* db, int rc) {
  const int code = rc & 0xff;
  const int os_error = sqlite3_system_errno(db);
  if (code == SQLITE_FULL || os_error == ENOSPC || os_error == EDQUOT) return StorageError::Kind::full;
  if (code == SQLITE_BUSY || code == SQLITE_LOCKED) return StorageError::Kind::unavailable;
  return StorageError::Kind::permanent;
}

}  // namespace

void fail(sqlite3* db, int rc, const std::string& what) {
  throw StorageError("database: " + what + ": " + sqlite3_errmsg(db), kind_of(db, rc));
}

void exec(sqlite3* db, const std::string& sql) {
  if (const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr); rc != SQLITE_OK) fail(db, rc, sql);
}

Statement::Statement(sqlite3* db, const std::string& sql) : db_(db) {
  if (const int rc = sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr); rc != SQLITE_OK)
    fail(db, rc, "cannot prepare a statement");
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

Statement& Statement::bind(int i, const std::string& v) {
  sqlite3_bind_text(stmt_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
  return *this;
}

Statement& Statement::bind(int i, long long v) {
  sqlite3_bind_int64(stmt_, i, v);
  return *this;
}

Statement& Statement::bind(int i, double v) {
  sqlite3_bind_double(stmt_, i, v);
  return *this;
}

Statement& Statement::bind_null(int i) {
  sqlite3_bind_null(stmt_, i);
  return *this;
}

int Statement::columns() const { return sqlite3_column_count(stmt_); }

bool Statement::step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  fail(db_, rc, "a query failed");
}

bool Statement::run() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_DONE) return true;
  if ((rc & 0xff) == SQLITE_CONSTRAINT) return false;
  fail(db_, rc, "a write failed");
}

std::string Statement::text(int col) const {
  const auto* p = sqlite3_column_text(stmt_, col);
  return p ? std::string(reinterpret_cast<const char*>(p), static_cast<std::size_t>(sqlite3_column_bytes(stmt_, col)))
           : "";
}

long long Statement::integer(int col) const { return sqlite3_column_int64(stmt_, col); }
double Statement::real(int col) const { return sqlite3_column_double(stmt_, col); }
bool Statement::is_null(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }

Transaction::Transaction(sqlite3* db) : db_(db) { exec(db_, "BEGIN IMMEDIATE"); }

Transaction::~Transaction() {
  if (!committed_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  exec(db_, "COMMIT");
  committed_ = true;
}

int changes(sqlite3* db) { return sqlite3_changes(db); }

}  // namespace meshmark::server::sqlite
