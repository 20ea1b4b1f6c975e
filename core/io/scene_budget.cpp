#include "core/io/scene_budget.hpp"

#include "core/io/mesh_io_error.hpp"

namespace meshmark {

void SceneBudget::fail(const std::string& what) const {
  throw MeshLimitError(source_ + ": " + what + " (a node or component hierarchy that repeats itself?)");
}

void SceneBudget::visit() {
  if (++placements_ > kMaxScenePlacements)
    fail("the scene places more than " + std::to_string(kMaxScenePlacements) + " nodes or components");
  if (placements_ % 1024 == 0) poll(limits_.control);
}

void SceneBudget::add_instance(std::size_t vertices, std::size_t faces) {
  if (++instances_ > kMaxFurtherInstances)
    fail("the scene draws its meshes more than " + std::to_string(kMaxFurtherInstances) + " times over");
  vertices_ += vertices;
  faces_ += faces;
  if (vertices_ > limits_.max_vertices)
    fail("the scene's instances hold more than " + std::to_string(limits_.max_vertices) + " vertices");
  if (faces_ > limits_.max_faces)
    fail("the scene's instances hold more than " + std::to_string(limits_.max_faces) + " faces");
  poll(limits_.control);
}

}  // namespace meshmark
