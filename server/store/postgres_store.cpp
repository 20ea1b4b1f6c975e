#include "server/store/postgres_store.hpp"

#include "server/store/postgres_database.hpp"

namespace meshmark::server {

PostgresStore::PostgresStore(const std::string& conninfo, const Clock& clock)
    : SqlStore(std::make_unique<PostgresDatabase>(conninfo), clock) {}

}  // namespace meshmark::server
