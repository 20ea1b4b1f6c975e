#include "server/store/sqlite_store.hpp"

#include "server/store/sqlite_database.hpp"

namespace meshmark::server {

SqliteStore::SqliteStore(const std::filesystem::path& file, const Clock& clock)
    : SqlStore(std::make_unique<SqliteDatabase>(file), clock) {}

}  // namespace meshmark::server
