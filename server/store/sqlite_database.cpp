#include "server/store/sqlite_database.hpp"

#include <sqlite3.h>

#include <stdexcept>

#include "server/store/sqlite_db.hpp"
#include "server/store/sqlite_schema.hpp"

namespace meshmark::server {

namespace {

class SqliteSession : public sql::Session {
 public:
  explicit SqliteSession(sqlite3* db) : db_(db) {}

  sql::Rows query(const std::string& text, const sql::Params& params) override {
    sqlite::Statement s = prepared(text, params);
    sql::Rows rows;
    while (s.step()) {
      std::vector<std::optional<std::string>> columns(static_cast<std::size_t>(s.columns()));
      for (int c = 0; c < s.columns(); ++c)
        if (!s.is_null(c)) columns[static_cast<std::size_t>(c)] = s.text(c);
      rows.emplace_back(std::move(columns));
    }
    return rows;
  }

  std::optional<long long> execute(const std::string& text, const sql::Params& params) override {
    sqlite::Statement s = prepared(text, params);
    if (!s.run()) return std::nullopt;
    return sqlite::changes(db_);
  }

 private:
  sqlite::Statement prepared(const std::string& text, const sql::Params& params) {
    sqlite::Statement s(db_, text);
    for (std::size_t i = 0; i < params.size(); ++i) {
      const int at = static_cast<int>(i) + 1;
      std::visit(
          [&](const auto& value) {
            if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::nullptr_t>) s.bind_null(at);
            else s.bind(at, value);
          },
          params[i]);
    }
    return s;
  }

  sqlite3* db_;
};

}  // namespace

SqliteDatabase::SqliteDatabase(const std::filesystem::path& file) {
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

SqliteDatabase::~SqliteDatabase() { sqlite3_close(db_); }

void SqliteDatabase::transaction(const std::function<bool(sql::Session&)>& work) {
  std::lock_guard lock(mutex_);
  sqlite::Transaction transaction(db_);
  SqliteSession session(db_);
  if (work(session)) transaction.commit();
}

void SqliteDatabase::run(const std::function<void(sql::Session&)>& work) {
  std::lock_guard lock(mutex_);
  SqliteSession session(db_);
  work(session);
}

bool SqliteDatabase::healthy() {
  std::lock_guard lock(mutex_);
  try {
    sqlite::Statement s(db_, "SELECT 1");
    return s.step();
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace meshmark::server
