#pragma once
// The shared store: the records (sql_store.hpp) in PostgreSQL (postgres_database.hpp), for
// several daemons at once.

#include <string>

#include "server/store/sql_store.hpp"

namespace meshmark::server {

class PostgresStore : public SqlStore {
 public:
  /// `conninfo`: libpq's connection string or URI. Throws StorageError when the server does not
  /// answer, std::runtime_error for a newer schema.
  explicit PostgresStore(const std::string& conninfo, const Clock& clock = system_clock(), std::size_t connections = 8);
};

}  // namespace meshmark::server
