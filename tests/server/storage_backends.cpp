#include "tests/server/storage_backends.hpp"

#include "server/store/sqlite_store.hpp"

namespace meshmark::test {

std::vector<StoreBackend> store_backends() {
  return {{"sqlite", [](const std::filesystem::path& place, const server::Clock& clock) {
             return std::make_unique<server::SqliteStore>(place / "meshmark.db", clock);
           }}};
}

std::vector<BlobBackend> blob_backends() {
  return {{"folder", [](const std::filesystem::path& place) {
             return std::make_unique<server::LocalBlobStore>(place / "blobs");
           }}};
}

}  // namespace meshmark::test
