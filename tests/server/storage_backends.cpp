#include "tests/server/storage_backends.hpp"

#include <cstdlib>

#include "server/store/s3_blob_store.hpp"
#include "server/store/sqlite_store.hpp"

namespace meshmark::test {

std::vector<StoreBackend> store_backends() {
  return {{"sqlite", [](const std::filesystem::path& place, const server::Clock& clock) {
             return std::make_unique<server::SqliteStore>(place / "meshmark.db", clock);
           }}};
}

std::vector<BlobBackend> blob_backends() {
  std::vector<BlobBackend> backends = {{"folder", [](const std::filesystem::path& place) {
                                          return std::make_unique<server::LocalBlobStore>(place / "blobs");
                                        }}};
  // The S3-compatible server the test command starts (deploy/s3-test-server.sh), its bucket made
  // at its start; each test's place is its own prefix.
  backends.push_back({"s3",
                      [](const std::filesystem::path& place) {
                        server::S3Location l{std::getenv("MESHMARK_TEST_S3_ENDPOINT"), "us-east-1", "meshmark-test",
                                             "tests/" + place.filename().string(),     "S3RVER",    "S3RVER"};
                        return std::make_unique<server::S3BlobStore>(l);
                      },
                      [] {
                        return std::string(std::getenv("MESHMARK_TEST_S3_ENDPOINT")
                                               ? ""
                                               : "no S3-compatible server (MESHMARK_TEST_S3_ENDPOINT)");
                      }});
  return backends;
}

}  // namespace meshmark::test
