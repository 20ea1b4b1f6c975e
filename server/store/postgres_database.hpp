#pragma once
// PostgreSQL behind sql::Database, through libpq: a small pool of connections shared by the
// daemon's threads, each reconnected when the server dropped it (a restart, pg_terminate_backend),
// the failing call answered as StorageError unavailable so that it is retried, not lost. The
// schema is brought up to date at open under an advisory lock (postgres_schema.hpp), so daemons
// starting at once migrate it once.

#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

#include "server/store/sql_database.hpp"

struct pg_conn;

namespace meshmark::server {

/// One connection to `conninfo`, its notices to the log; throws StorageError (unavailable).
pg_conn* postgres_connect(const std::string& conninfo);

class PostgresDatabase : public sql::Database {
 public:
  /// `conninfo`: a libpq connection string or URI ("postgresql://user@host/db"). Throws
  /// StorageError when the server cannot be reached.
  explicit PostgresDatabase(std::string conninfo, std::size_t connections = 8);
  ~PostgresDatabase() override;
  PostgresDatabase(const PostgresDatabase&) = delete;
  PostgresDatabase& operator=(const PostgresDatabase&) = delete;

  void transaction(const std::function<bool(sql::Session&)>& work) override;
  void run(const std::function<void(sql::Session&)>& work) override;
  bool healthy() override;
  void announce(sql::Session& session, const std::string& channel) override;
  std::unique_ptr<Subscription> listen(const std::string& channel, std::function<void()> heard) override;
  std::string skip_locked(const std::string& table) const override {
    return " FOR UPDATE OF " + table + " SKIP LOCKED";
  }

 private:
  pg_conn* acquire();
  void release(pg_conn* connection);
  template <typename Work>
  void with_connection(Work&& work);

  const std::string conninfo_;
  const std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable returned_;
  std::vector<pg_conn*> idle_;
  std::size_t open_ = 0;
};

}  // namespace meshmark::server
