#pragma once
// Prepares a model from its stored original — parameterization, grid, carriers — stores the
// preparation beside it and hands it to the cache: what the prepare job runs. Jobs that use a
// model get it from prepared(), which loads it and only rebuilds a preparation the store lost or
// that an older version wrote (derived data, DESIGN.md "Caches are derived data").

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "server/model_cache.hpp"
#include "server/store/blob_store.hpp"

namespace meshmark::server {

class ModelPreparer {
 public:
  ModelPreparer(BlobStore& blobs, ModelCache& cache) : blobs_(blobs), cache_(cache) {}

  /// Prepares the model and stores and keeps the result (one preparation per model at a time).
  /// Throws what prepare_model throws, or std::runtime_error when the original is missing.
  std::shared_ptr<const PreparedEntry> prepare(const std::string& model_id, const JobControl* control);
  /// The prepared model for a job that uses it (see above).
  std::shared_ptr<const PreparedEntry> prepared(const std::string& model_id, const JobControl* control);

 private:
  BlobStore& blobs_;
  ModelCache& cache_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<std::mutex>> preparing_;
};

}  // namespace meshmark::server
