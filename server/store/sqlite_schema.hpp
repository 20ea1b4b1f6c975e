#pragma once
// The embedded store's schema as numbered migrations, applied in order at open, each in its own
// transaction with the version (PRAGMA user_version) it brings; a database from a newer meshmark
// is refused rather than guessed around.

struct sqlite3;

namespace meshmark::server::sqlite {

/// The version the migrations bring a database to.
int latest_schema_version();

/// Brings the database to latest_schema_version(). Throws std::runtime_error when it is newer.
void migrate(sqlite3* db);

}  // namespace meshmark::server::sqlite
