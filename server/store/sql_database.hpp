#pragma once
// What the store needs of a SQL database, whatever the engine: statements with `?` parameters,
// results as text, transactions. SqlStore (sql_store.hpp) writes the daemon's records once over
// this; SQLite (sqlite_database.hpp) and PostgreSQL (postgres_database.hpp) each translate it.
// Failures throw StorageError of the right kind.

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "server/store/subscription.hpp"

namespace meshmark::server::sql {

using Param = std::variant<std::string, long long, double, std::nullptr_t>;
using Params = std::vector<Param>;

/// One result row, every column as the text the engine gives (NULL: absent).
class Row {
 public:
  explicit Row(std::vector<std::optional<std::string>> columns) : columns_(std::move(columns)) {}
  std::string text(std::size_t column) const { return columns_.at(column).value_or(""); }
  long long integer(std::size_t column) const;
  double real(std::size_t column) const;
  bool is_null(std::size_t column) const { return !columns_.at(column); }

 private:
  std::vector<std::optional<std::string>> columns_;
};
using Rows = std::vector<Row>;

/// One connection, for one call or one transaction.
class Session {
 public:
  virtual ~Session() = default;
  virtual Rows query(const std::string& sql, const Params& params = {}) = 0;
  /// Rows changed; nullopt when a constraint refused the statement (e.g. a duplicate key).
  virtual std::optional<long long> execute(const std::string& sql, const Params& params = {}) = 0;
};

class Database {
 public:
  virtual ~Database() = default;
  /// Runs `work` in one transaction on one connection: committed when it returns true, rolled
  /// back when it returns false or throws.
  virtual void transaction(const std::function<bool(Session&)>& work) = 0;
  /// Runs `work` on one connection, each statement committed on its own.
  virtual void run(const std::function<void(Session&)>& work) = 0;
  /// A cheap query that proves the database answers.
  virtual bool healthy() = 0;
  /// What ends a SELECT whose rows the transaction takes for itself, skipping rows another
  /// transaction holds ("FOR UPDATE OF t SKIP LOCKED"); empty where writers are serialized anyway
  /// (SQLite).
  virtual std::string skip_locked(const std::string& table) const = 0;
  /// Tells whoever listens on `channel` (listen) when `session`'s transaction commits; nothing
  /// where no other process could listen (SQLite: one daemon).
  virtual void announce(Session& session, const std::string& channel) {
    (void)session;
    (void)channel;
  }
  /// Calls `heard` after commits that announced on `channel`, until the subscription is destroyed;
  /// nullptr where nothing is ever announced.
  // NOLINTNEXTLINE(performance-unnecessary-value-param): a sink, which the overrides keep
  virtual std::unique_ptr<Subscription> listen(const std::string& /*channel*/, std::function<void()> /*heard*/) {
    return nullptr;
  }
};

}  // namespace meshmark::server::sql
