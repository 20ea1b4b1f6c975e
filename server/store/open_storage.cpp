#include "server/store/open_storage.hpp"

#include <stdexcept>

#include "server/store/postgres_store.hpp"
#include "server/store/s3_blob_store.hpp"
#include "server/store/sqlite_store.hpp"

namespace meshmark::server {

namespace {

struct Location {
  std::string scheme, rest;
};

Location split(const std::string& location) {
  const auto colon = location.find(':');
  if (colon == std::string::npos || colon == 0) return {};
  std::string rest = location.substr(colon + 1);
  if (rest.rfind("//", 0) == 0) rest.erase(0, 2);  // scheme:///abs/path → /abs/path
  return {location.substr(0, colon), rest};
}

[[noreturn]] void refuse(const char* what, const std::string& location, const char* known) {
  const std::string scheme = split(location).scheme;
  throw std::invalid_argument(std::string(what) + ": " + (scheme.empty() ? "no scheme" : "'" + scheme + ":'") +
                              " is not a location this meshmarkd knows; use " + known);
}

}  // namespace

std::unique_ptr<Store> open_store(const std::string& location, const std::filesystem::path& data_dir,
                                  const Clock& clock) {
  if (location.empty()) return std::make_unique<SqliteStore>(data_dir / "meshmark.db", clock);
  const Location l = split(location);
  if (l.scheme == "sqlite" && !l.rest.empty()) return std::make_unique<SqliteStore>(l.rest, clock);
  if (l.scheme == "postgresql" || l.scheme == "postgres") return std::make_unique<PostgresStore>(location, clock);
  refuse("--store", location, "sqlite:PATH or postgresql://USER@HOST:PORT/DATABASE");
}

std::unique_ptr<BlobStore> open_blob_store(const std::string& location, const std::filesystem::path& data_dir) {
  if (location.empty()) return std::make_unique<LocalBlobStore>(data_dir / "blobs");
  const Location l = split(location);
  if (l.scheme == "file" && !l.rest.empty()) return std::make_unique<LocalBlobStore>(l.rest);
  if (l.scheme == "s3") return std::make_unique<S3BlobStore>(s3_location_from(location));
  refuse("--blobs", location, "file:PATH or s3://BUCKET/PREFIX");
}

bool shared_store(const std::string& location) {
  const std::string scheme = split(location).scheme;
  return scheme == "postgresql" || scheme == "postgres";
}

std::string describe_location(const std::string& location) {
  if (location.empty()) return "the data folder";
  const Location l = split(location);
  if (l.scheme == "sqlite" || l.scheme == "file") return location;
  const auto at = l.rest.find('@');
  const std::string host = l.rest.substr(at == std::string::npos ? 0 : at + 1);
  return l.scheme + "://" + host.substr(0, host.find('/'));
}

}  // namespace meshmark::server
