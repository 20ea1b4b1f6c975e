#include "server/model_cache.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "core/io/read_mesh.hpp"
#include "core/watermark/prepared_model_io.hpp"
#include "server/store/blob_keys.hpp"

namespace meshmark::server {

std::shared_ptr<const PreparedEntry> ModelCache::get(const std::string& model_id, const JobControl* control) {
  std::shared_ptr<std::mutex> gate;
  {
    std::lock_guard lock(mutex_);
    for (auto it = lru_.begin(); it != lru_.end(); ++it)
      if (it->model_id == model_id) {
        lru_.splice(lru_.begin(), lru_, it);
        return it->entry;
      }
    auto& slot = loading_[model_id];
    if (!slot) slot = std::make_shared<std::mutex>();
    gate = slot;
  }
  std::lock_guard loading(*gate);  // a second job for the same model waits for the first
  {
    std::lock_guard lock(mutex_);
    for (const auto& kept : lru_)
      if (kept.model_id == model_id) return kept.entry;
  }
  try {
    auto entry = load(model_id, control);
    keep(model_id, entry);
    return entry;
  } catch (...) {
    std::lock_guard lock(mutex_);
    loading_.erase(model_id);  // waiters keep their copy of the gate
    throw;
  }
}

std::shared_ptr<const PreparedEntry> ModelCache::load(const std::string& model_id, const JobControl* control) {
  const auto original = blobs_.get(original_key(model_id));
  if (!original) throw std::runtime_error("the model's mesh is missing from the store");
  const auto stored = blobs_.get(prepared_key(model_id));
  if (!stored) throw ModelNotPrepared("the store holds no preparation of model " + model_id);
  Mesh mesh = read_mesh_from_memory(*original, MeshFormat::ply, {}, "stored model").mesh;
  try {
    return std::make_shared<const PreparedEntry>(deserialize_prepared_model(*stored, mesh, &grids_, control));
  } catch (const Canceled&) {
    throw;
  } catch (const TimeLimitExceeded&) {
    throw;
  } catch (const std::exception& e) {
    throw ModelNotPrepared("the stored preparation of model " + model_id + " cannot be used: " + e.what());
  }
}

void ModelCache::keep(const std::string& model_id, std::shared_ptr<const PreparedEntry> entry) {
  std::lock_guard lock(mutex_);
  loading_.erase(model_id);
  lru_.remove_if([&](const Kept& kept) { return kept.model_id == model_id; });
  const auto vertices = static_cast<std::size_t>(entry->model.mesh.V.rows());
  auto memory = room_for(kPreparedBytesPerVertex * vertices);
  if (!memory) {
    spdlog::info("model {}: not kept in memory (the memory ceiling has no room for it)", model_id);
    return;
  }
  lru_.push_front({model_id, std::move(entry), std::move(*memory), nullptr, {}});
  while (lru_.size() > capacity_) lru_.pop_back();
}

std::optional<MemoryReservation> ModelCache::room_for(std::size_t bytes) {
  while (memory_.available() < bytes && !lru_.empty()) lru_.pop_back();
  return memory_.try_reserve(bytes);
}

void ModelCache::make_room(std::size_t bytes) {
  std::lock_guard lock(mutex_);
  while (memory_.available() < bytes && !lru_.empty()) lru_.pop_back();
}

std::shared_ptr<const ParsedUpload> ModelCache::upload(const std::string& model_id, MeshFormat format) {
  std::lock_guard lock(mutex_);
  for (const Kept& kept : lru_)
    if (kept.model_id == model_id && kept.upload && kept.upload->format == format) return kept.upload;
  return nullptr;
}

void ModelCache::keep_upload(const std::string& model_id, std::shared_ptr<const ParsedUpload> upload,
                             std::size_t bytes) {
  std::lock_guard lock(mutex_);
  for (Kept& kept : lru_) {
    if (kept.model_id != model_id || kept.upload) continue;
    if (auto memory = memory_.try_reserve(bytes))
      kept.upload = std::move(upload), kept.upload_memory = std::move(*memory);
    return;
  }
}

void ModelCache::evict(const std::string& model_id) {
  std::lock_guard lock(mutex_);
  lru_.remove_if([&](const Kept& kept) { return kept.model_id == model_id; });
}

}  // namespace meshmark::server
