#include "tests/server/storage_backends.hpp"

#include <cstdlib>

#include <libpq-fe.h>

#include "core/util/keyed_random.hpp"
#include "server/store/postgres_store.hpp"
#include "server/store/s3_blob_store.hpp"
#include "server/store/sqlite_store.hpp"

namespace meshmark::test {

namespace {

std::string absent_unless(const char* variable, const char* what) {
  return std::getenv(variable) ? "" : std::string("no ") + what + " (" + variable + ")";
}

}  // namespace

std::string postgres_test_database(const std::filesystem::path& place) {
  const std::string admin = std::getenv("MESHMARK_TEST_POSTGRES");
  const auto digest = sha256(place.string());
  const std::string name = "mm_" + to_hex(digest.data(), 12);
  PGconn* c = PQconnectdb(admin.c_str());
  PGresult* r = PQexec(c, ("CREATE DATABASE " + name).c_str());  // 42P04: it exists (the place reopened)
  const char* state = PQresultErrorField(r, PG_DIAG_SQLSTATE);
  const bool made = PQresultStatus(r) == PGRES_COMMAND_OK || (state && std::string(state) == "42P04");
  const std::string error = PQerrorMessage(c);
  PQclear(r);
  PQfinish(c);
  if (!made) throw std::runtime_error("cannot make a test database: " + error);
  return admin.substr(0, admin.rfind('/') + 1) + name;
}

std::vector<StoreBackend> store_backends() {
  return {{"sqlite",
           [](const std::filesystem::path& place, const server::Clock& clock) {
             return std::make_unique<server::SqliteStore>(place / "meshmark.db", clock);
           }},
          // The PostgreSQL server the test command starts (deploy/postgres-test-server.sh).
          {"postgresql",
           [](const std::filesystem::path& place, const server::Clock& clock) {
             return std::make_unique<server::PostgresStore>(postgres_test_database(place), clock);
           },
           [] { return absent_unless("MESHMARK_TEST_POSTGRES", "PostgreSQL server"); }}};
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
                      [] { return absent_unless("MESHMARK_TEST_S3_ENDPOINT", "S3-compatible server"); }});
  return backends;
}

}  // namespace meshmark::test
