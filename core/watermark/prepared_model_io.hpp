#pragma once
// Storing a prepared model, so a service prepares each model once and keeps it across restarts.
// The file holds what prepare_model computed except the mesh (stored on its own) and the grid
// (rebuilt, or shared through a GridCache), and detection's nuisance fields (made here if no
// detection made them yet); it ends with a SHA-256 of its content.

#include <string>
#include <string_view>

#include "core/watermark/prepared_model.hpp"

namespace meshmark {

std::string serialize_prepared_model(const PreparedModel& model);

/// Rebuilds a prepared model from `bytes` and the original `mesh`. Throws std::runtime_error for
/// a truncated, corrupt or foreign file, or one prepared from another mesh. A bump basis is
/// rebuilt under `control` (its threads, its cancel).
PreparedModel deserialize_prepared_model(std::string_view bytes, const Mesh& mesh, GridCache* grids = nullptr,
                                         const JobControl* control = nullptr);

}  // namespace meshmark
