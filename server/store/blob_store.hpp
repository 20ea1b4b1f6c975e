#pragma once
// Large immutable files by key ("models/<id>/original.ply"): on local disk for the embedded
// default (written to a temporary name, fsynced, renamed), an object store in a shared
// deployment.

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace meshmark::server {

struct StoredBlob {
  std::string key;
  std::chrono::system_clock::time_point modified;
};
using BlobVisitor = std::function<void(const StoredBlob&)>;

class BlobStore {
 public:
  virtual ~BlobStore() = default;
  /// Durable when it returns.
  virtual void put(const std::string& key, const std::string& bytes) = 0;
  virtual std::optional<std::string> get(const std::string& key) = 0;
  /// Removes the blob `prefix` and every blob under the folder `prefix`/.
  virtual void remove_prefix(const std::string& prefix) = 0;
  /// Every blob in the folder `folder`/ and below, in no set order; a write under way is not one.
  virtual void list(const std::string& folder, const BlobVisitor& visit) = 0;
};

/// Keys are made by the daemon from its own identifiers; refuses (std::invalid_argument) any that
/// is empty, absolute or climbs out with "..".
void check_blob_key(const std::string& key);

class LocalBlobStore : public BlobStore {
 public:
  explicit LocalBlobStore(std::filesystem::path root);
  void put(const std::string& key, const std::string& bytes) override;
  std::optional<std::string> get(const std::string& key) override;
  void remove_prefix(const std::string& prefix) override;
  void list(const std::string& folder, const BlobVisitor& visit) override;

 private:
  std::filesystem::path path_of(const std::string& key) const;
  std::filesystem::path root_;
};

}  // namespace meshmark::server
