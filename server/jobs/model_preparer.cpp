#include "server/jobs/model_preparer.hpp"

#include <spdlog/spdlog.h>

#include "core/io/read_mesh.hpp"
#include "core/watermark/prepared_model_io.hpp"
#include "server/store/blob_keys.hpp"

namespace meshmark::server {

std::shared_ptr<const PreparedEntry> ModelPreparer::prepare(const std::string& model_id, const JobControl* control) {
  std::shared_ptr<std::mutex> gate;
  {
    std::lock_guard lock(mutex_);
    auto& slot = preparing_[model_id];
    if (!slot) slot = std::make_shared<std::mutex>();
    gate = slot;
  }
  std::lock_guard preparing(*gate);
  struct Forget {  // the gate goes with the last preparation (waiters keep their copy)
    ModelPreparer& self;
    const std::string& id;
    ~Forget() {
      std::lock_guard lock(self.mutex_);
      self.preparing_.erase(id);
    }
  } forget{*this, model_id};
  const auto original = blobs_.get(original_key(model_id));
  if (!original) throw std::runtime_error("the model's mesh is missing from the store");
  const Mesh mesh = read_mesh_from_memory(*original, MeshFormat::ply, {}, "stored model").mesh;
  PreparedModel model = prepare_model(mesh, {}, control, &cache_.grids());
  blobs_.put(prepared_key(model_id), serialize_prepared_model(model));
  auto entry = std::make_shared<const PreparedEntry>(std::move(model));
  cache_.keep(model_id, entry);
  return entry;
}

std::shared_ptr<const PreparedEntry> ModelPreparer::prepared(const std::string& model_id, const JobControl* control) {
  try {
    return cache_.get(model_id, control);
  } catch (const ModelNotPrepared& e) {
    spdlog::warn("{}; preparing it again", e.what());
    return prepare(model_id, control);
  }
}

}  // namespace meshmark::server
