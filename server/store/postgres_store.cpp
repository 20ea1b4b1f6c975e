#include "server/store/postgres_store.hpp"

#include "server/store/postgres_database.hpp"

namespace meshmark::server {

PostgresStore::PostgresStore(const std::string& conninfo, const Clock& clock, std::size_t connections)
    : SqlStore(std::make_unique<PostgresDatabase>(conninfo, connections), clock) {}

}  // namespace meshmark::server
