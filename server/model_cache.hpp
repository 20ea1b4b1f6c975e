#pragma once
// Prepared models (and their registration data) in memory, least recently used first out,
// backed by the blob store: a model is prepared once, stored, and after a restart loaded back.

#include <atomic>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "core/registration/align_meshes.hpp"
#include "core/watermark/prepared_model.hpp"
#include "server/store/blob_store.hpp"

namespace meshmark::server {

struct PreparedEntry {
  explicit PreparedEntry(PreparedModel m) : model(std::move(m)), target(model.outward_mesh()) {}
  PreparedModel model;
  RegistrationTarget target;
  /// A copy of this model was read back through registration after the mild attack
  /// (VerifyOptions::registration_proven): later copies are verified in place.
  mutable std::atomic<bool> registration_proven{false};
};

/// Blob keys of a model's files (all under model_prefix).
std::string model_prefix(const std::string& model_id);
/// The model's surface (welded, binary PLY): what it is prepared from.
std::string original_key(const std::string& model_id);
/// The file as uploaded, byte for byte: what marked copies are written from. (Absent for models
/// uploaded before the daemon kept it: their copies are written from the surface.)
std::string upload_key(const std::string& model_id);
std::string prepared_key(const std::string& model_id);

class ModelCache {
 public:
  ModelCache(BlobStore& blobs, std::size_t capacity) : blobs_(blobs), capacity_(capacity) {}

  /// The prepared model: from memory, from the blob store, or prepared now (and stored).
  /// Throws what prepare_model throws, or std::runtime_error when the original is missing.
  std::shared_ptr<const PreparedEntry> get(const std::string& model_id, const JobControl* control = nullptr);
  void evict(const std::string& model_id);

 private:
  std::shared_ptr<const PreparedEntry> load_or_prepare(const std::string& model_id, const JobControl* control);
  void remember(const std::string& model_id, std::shared_ptr<const PreparedEntry> entry);

  BlobStore& blobs_;
  GridCache grids_;
  const std::size_t capacity_;
  std::mutex mutex_;
  std::list<std::pair<std::string, std::shared_ptr<const PreparedEntry>>> lru_;  // most recent first
  std::map<std::string, std::shared_ptr<std::mutex>> preparing_;                 // one preparation per model
};

}  // namespace meshmark::server
