#pragma once
// Prepared models (and their registration data) in memory, least recently used first out,
// backed by the blob store, each with its upload once an embed parsed it. The cache only loads:
// preparing is the prepare job's (server/jobs/model_preparer.hpp), which hands the result over
// with keep(), and parsing an upload the embed job's, which hands it over with keep_upload().

#include <atomic>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/io/document_surface.hpp"
#include "core/io/packaged_document.hpp"
#include "core/registration/align_meshes.hpp"
#include "core/watermark/prepared_model.hpp"
#include "server/memory_budget.hpp"
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

/// A model's upload parsed for writing its copies into (the upload with moved positions), and
/// its welded surface, which must be the prepared model's.
struct ParsedUpload {
  ParsedUpload(std::string bytes, MeshFormat format, const DocumentReadOptions& options)
      : format(format),
        document(std::move(bytes), format, options, "the model's file"),
        surface(document_surface(document.document())) {}
  MeshFormat format;
  PackagedDocument document;
  WeldedSurface surface;
};

/// The blob store holds no preparation of the model this version can read: none yet, or one of
/// an older format or damaged (it is derived data, rebuilt by the preparer).
class ModelNotPrepared : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Keeps at most `capacity` models, each charged to the memory budget while kept: when the budget
/// has no room for a new one, the least recently used make room, and a model that still does not
/// fit is handed out without being kept.
class ModelCache {
 public:
  ModelCache(BlobStore& blobs, std::size_t capacity, MemoryBudget& memory)
      : blobs_(blobs), capacity_(capacity), memory_(memory) {}

  /// The prepared model: from memory, else loaded from the blob store (one load per model at a
  /// time) and kept. Throws ModelNotPrepared, or std::runtime_error when the original is missing.
  std::shared_ptr<const PreparedEntry> get(const std::string& model_id, const JobControl* control = nullptr);
  /// Keeps a model just prepared (and stored).
  void keep(const std::string& model_id, std::shared_ptr<const PreparedEntry> entry);
  void evict(const std::string& model_id);
  /// The model's parsed upload in `format`, kept beside the model since an embed parsed it; none
  /// when not kept. Parsing and welding it for every copy was most of an embed job's time.
  std::shared_ptr<const ParsedUpload> upload(const std::string& model_id, MeshFormat format);
  /// Keeps `upload`, charged `bytes`, beside the model while the model is kept, when the ceiling
  /// has room for it now (it makes none: a job or an upload comes first).
  void keep_upload(const std::string& model_id, std::shared_ptr<const ParsedUpload> upload, std::size_t bytes);
  /// The sampling grids every model's preparation and loading share.
  GridCache& grids() { return grids_; }
  /// Drops the least recently used models until `bytes` are free under the memory ceiling (or
  /// none is kept): what an upload or a job needs comes before a model kept for later.
  void make_room(std::size_t bytes);

 private:
  std::shared_ptr<const PreparedEntry> load(const std::string& model_id, const JobControl* control);
  std::optional<MemoryReservation> room_for(std::size_t bytes);  // under mutex_

  struct Kept {
    std::string model_id;
    std::shared_ptr<const PreparedEntry> entry;
    MemoryReservation memory;
    std::shared_ptr<const ParsedUpload> upload;  ///< none until an embed parsed it
    MemoryReservation upload_memory;
  };

  BlobStore& blobs_;
  GridCache grids_;
  const std::size_t capacity_;
  MemoryBudget& memory_;
  std::mutex mutex_;
  std::list<Kept> lru_;                                         // most recent first
  std::map<std::string, std::shared_ptr<std::mutex>> loading_;  // one load per model
};

}  // namespace meshmark::server
