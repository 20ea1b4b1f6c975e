#pragma once
// The store and the blob store a daemon's configuration names: the one place that knows every
// backend. A location is SCHEME:REST; the embedded defaults live in the data folder.

#include <filesystem>
#include <memory>
#include <string>

#include "server/clock.hpp"
#include "server/store/blob_store.hpp"
#include "server/store/store.hpp"

namespace meshmark::server {

/// "sqlite:PATH" (also "sqlite://" + an absolute path); empty: DATA/meshmark.db;
/// "postgresql://…" (libpq's URI: user, password, host, port, database, parameters). Throws
/// std::invalid_argument naming what is understood (never echoing the location: it may hold a
/// password).
std::unique_ptr<Store> open_store(const std::string& location, const std::filesystem::path& data_dir,
                                  const Clock& clock);

/// "file:PATH" (also "file://" + an absolute path); empty: DATA/blobs. "s3://BUCKET/PREFIX": an
/// S3-compatible object store (s3_blob_store.hpp says where its endpoint and credentials come from).
std::unique_ptr<BlobStore> open_blob_store(const std::string& location, const std::filesystem::path& data_dir);

/// Whether daemons may share the store at `location` (then each claims the others' queued work).
bool shared_store(const std::string& location);

/// What the log and /metrics may say of a location: its scheme and host, no credentials.
std::string describe_location(const std::string& location);

}  // namespace meshmark::server
