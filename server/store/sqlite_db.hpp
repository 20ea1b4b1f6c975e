#pragma once
// Thin RAII over the SQLite C API for the embedded store: a prepared statement, a transaction,
// and every failure turned into a StorageError of the right kind.

#include <string>

struct sqlite3;
struct sqlite3_stmt;

namespace meshmark::server::sqlite {

/// Throws the StorageError for a failed call: full (disk or quota), unavailable (busy, locked)
/// or permanent.
[[noreturn]] void fail(sqlite3* db, int rc, const std::string& what);

/// Runs one or more statements without results.
void exec(sqlite3* db, const std::string& sql);

class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement& operator=(Statement&&) = delete;

  Statement& bind(int i, const std::string& v);
  Statement& bind(int i, long long v);
  Statement& bind(int i, double v);
  Statement& bind_null(int i);
  Statement(Statement&& other) noexcept : db_(other.db_), stmt_(other.stmt_) { other.stmt_ = nullptr; }
  int columns() const;
  /// True while a row is available.
  bool step();
  /// Runs to completion; false on a constraint violation (e.g. a duplicate key).
  bool run();
  std::string text(int col) const;
  long long integer(int col) const;
  double real(int col) const;
  bool is_null(int col) const;

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

/// BEGIN IMMEDIATE … COMMIT; rolls back unless commit() was reached (an error or an early return).
class Transaction {
 public:
  explicit Transaction(sqlite3* db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  sqlite3* db_;
  bool committed_ = false;
};

/// Rows the last statement changed.
int changes(sqlite3* db);

}  // namespace meshmark::server::sqlite
