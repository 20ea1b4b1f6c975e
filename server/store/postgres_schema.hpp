#pragma once
// The PostgreSQL schema as numbered migrations, applied in order at open, each in its own
// transaction recorded in schema_version, all under an advisory lock so that daemons starting at
// once apply each exactly once; a database from a newer meshmark is refused.

#include "server/store/sql_database.hpp"

namespace meshmark::server::postgres {

int latest_schema_version();

/// Brings the database to latest_schema_version() on this session's connection.
void migrate(sql::Session& session);

}  // namespace meshmark::server::postgres
