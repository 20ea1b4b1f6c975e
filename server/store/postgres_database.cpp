#include "server/store/postgres_database.hpp"

#include <libpq-fe.h>
#include <spdlog/spdlog.h>

#include <charconv>
#include <memory>
#include <stdexcept>

#include "server/store/postgres_listener.hpp"
#include "server/store/postgres_schema.hpp"
#include "server/store/storage_error.hpp"

namespace meshmark::server {

namespace {

using Result = std::unique_ptr<PGresult, void (*)(PGresult*)>;

// SQLSTATE classes: 23 integrity (a duplicate key: not an error for the caller), 08 connection,
// 40 transaction rollback (serialization, deadlock), 53 resources (53100: disk full), 57P admin
// shutdown, 55P03 lock not available.
StorageError::Kind kind_of(const std::string& state, bool connection_lost) {
  if (state == "53100") return StorageError::Kind::full;
  if (connection_lost || state.rfind("08", 0) == 0 || state.rfind("40", 0) == 0 || state.rfind("53", 0) == 0 ||
      state.rfind("57P", 0) == 0 || state == "55P03")
    return StorageError::Kind::unavailable;
  return StorageError::Kind::permanent;
}

// "… WHERE a = ? AND b = ?" → "… WHERE a = $1 AND b = $2" (no statement of ours has a '?' in a literal).
std::string numbered(const std::string& sql) {
  std::string out;
  out.reserve(sql.size() + 16);
  int n = 0;
  for (const char c : sql) {
    if (c == '?') out += "$" + std::to_string(++n);
    else out += c;
  }
  return out;
}

std::optional<std::string> param_text(const sql::Param& p) {
  return std::visit(
      [](const auto& v) -> std::optional<std::string> {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, std::nullptr_t>) return std::nullopt;
        else if constexpr (std::is_same_v<V, std::string>) return v;
        else if constexpr (std::is_same_v<V, long long>) return std::to_string(v);
        else {
          char buffer[64];
          const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;  // shortest exact
          return std::string(buffer, end);
        }
      },
      p);
}

// The connection was gone before the session's first statement reached the server (ended while
// idle in the pool): nothing ran, so the work may be tried again on a new connection.
class LostBeforeFirstStatement : public StorageError {
 public:
  explicit LostBeforeFirstStatement(const std::string& what) : StorageError(what, Kind::unavailable) {}
};

class PostgresSession : public sql::Session {
 public:
  explicit PostgresSession(PGconn* connection) : connection_(connection) {}

  sql::Rows query(const std::string& sql, const sql::Params& params) override {
    const Result r = perform(sql, params);
    if (!r) throw StorageError("database: a query broke a constraint", StorageError::Kind::permanent);
    sql::Rows rows;
    const int columns = PQnfields(r.get());
    for (int i = 0; i < PQntuples(r.get()); ++i) {
      std::vector<std::optional<std::string>> row(static_cast<std::size_t>(columns));
      for (int c = 0; c < columns; ++c)
        if (!PQgetisnull(r.get(), i, c))
          row[static_cast<std::size_t>(c)] =
              std::string(PQgetvalue(r.get(), i, c), static_cast<std::size_t>(PQgetlength(r.get(), i, c)));
      rows.emplace_back(std::move(row));
    }
    return rows;
  }

  std::optional<long long> execute(const std::string& sql, const sql::Params& params) override {
    const Result r = perform(sql, params);
    if (!r) return std::nullopt;
    const char* changed = PQcmdTuples(r.get());
    return *changed ? std::stoll(changed) : 0;
  }

  // The statement's result; null when a constraint refused it (SQLSTATE class 23).
  Result perform(const std::string& sql, const sql::Params& params) {
    std::vector<std::optional<std::string>> texts;
    std::vector<const char*> values;
    for (const sql::Param& p : params) texts.push_back(param_text(p));
    for (const auto& t : texts) values.push_back(t ? t->c_str() : nullptr);
    // Without parameters, the simple protocol: it also takes several statements at once (migrations).
    Result r(params.empty() ? PQexec(connection_, sql.c_str())
                            : PQexecParams(connection_, numbered(sql).c_str(), static_cast<int>(values.size()), nullptr,
                                           values.data(), nullptr, nullptr, 0),
             PQclear);
    const ExecStatusType status = r ? PQresultStatus(r.get()) : PGRES_FATAL_ERROR;
    const bool first = statements_++ == 0;
    if (status == PGRES_TUPLES_OK || status == PGRES_COMMAND_OK) return r;
    if (first && PQstatus(connection_) != CONNECTION_OK)
      throw LostBeforeFirstStatement("database: " + std::string(PQerrorMessage(connection_)));
    const char* field = r ? PQresultErrorField(r.get(), PG_DIAG_SQLSTATE) : nullptr;
    const std::string state = field ? field : "";
    if (state.rfind("23", 0) == 0) return Result(nullptr, PQclear);
    throw StorageError("database: " + std::string(PQerrorMessage(connection_)),
                       kind_of(state, PQstatus(connection_) != CONNECTION_OK));
  }

 private:
  PGconn* connection_;
  int statements_ = 0;
};

// The server's notices ("relation … already exists, skipping") go to the log, not to stderr.
void log_notice(void*, const char* message) { spdlog::debug("database: {}", message); }

}  // namespace

PGconn* postgres_connect(const std::string& conninfo) {
  PGconn* c = PQconnectdb(conninfo.c_str());
  if (PQstatus(c) != CONNECTION_OK) {
    const std::string error = c ? PQerrorMessage(c) : "out of memory";
    PQfinish(c);
    throw StorageError("database: cannot connect: " + error, StorageError::Kind::unavailable);
  }
  PQsetNoticeProcessor(c, log_notice, nullptr);
  return c;
}

PostgresDatabase::PostgresDatabase(std::string conninfo, std::size_t connections)
    : conninfo_(std::move(conninfo)), capacity_(std::max<std::size_t>(1, connections)) {
  PGconn* c = acquire();
  try {
    PostgresSession session(c);
    postgres::migrate(session);
  } catch (...) {
    release(c);
    throw;
  }
  release(c);
}

PostgresDatabase::~PostgresDatabase() {
  for (PGconn* c : idle_) PQfinish(c);
}

PGconn* PostgresDatabase::acquire() {
  std::unique_lock lock(mutex_);
  returned_.wait(lock, [&] { return !idle_.empty() || open_ < capacity_; });
  if (!idle_.empty()) {
    PGconn* c = idle_.back();
    idle_.pop_back();
    lock.unlock();
    // Ended by the server while idle here (a restart, pg_terminate_backend): what it sent then
    // makes it bad now, and it is reopened before a statement is lost on it.
    if (PQconsumeInput(c) == 0 || PQstatus(c) != CONNECTION_OK) PQreset(c);
    return c;
  }
  ++open_;
  lock.unlock();
  try {
    return postgres_connect(conninfo_);
  } catch (...) {
    std::lock_guard again(mutex_);
    --open_;
    returned_.notify_one();
    throw;
  }
}

void PostgresDatabase::release(PGconn* c) {
  {
    std::lock_guard lock(mutex_);
    idle_.push_back(c);
  }
  returned_.notify_one();
}

template <typename Work>
void PostgresDatabase::with_connection(Work&& work) {
  for (int attempt = 0;; ++attempt) {
    PGconn* c = acquire();
    try {
      work(c);
      release(c);
      return;
    } catch (const LostBeforeFirstStatement&) {
      release(c);  // reopened by the next acquire
      if (attempt > 0) throw;
    } catch (...) {
      release(c);
      throw;
    }
  }
}

void PostgresDatabase::transaction(const std::function<bool(sql::Session&)>& work) {
  with_connection([&](PGconn* c) {
    PostgresSession session(c);
    session.execute("BEGIN", {});
    try {
      session.execute(work(session) ? "COMMIT" : "ROLLBACK", {});
    } catch (...) {
      PQclear(PQexec(c, "ROLLBACK"));  // on a lost connection this fails too, and the server rolled back
      throw;
    }
  });
}

void PostgresDatabase::run(const std::function<void(sql::Session&)>& work) {
  with_connection([&](PGconn* c) {
    PostgresSession session(c);
    work(session);
  });
}

void PostgresDatabase::announce(sql::Session& session, const std::string& channel) {
  session.query("SELECT pg_notify(?, '')", {channel});
}

std::unique_ptr<Subscription> PostgresDatabase::listen(const std::string& channel, std::function<void()> heard) {
  return std::make_unique<PostgresListener>(conninfo_, channel, std::move(heard));
}

bool PostgresDatabase::healthy() {
  try {
    bool answered = false;
    run([&](sql::Session& s) { answered = !s.query("SELECT 1").empty(); });
    return answered;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace meshmark::server
