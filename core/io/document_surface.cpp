#include "core/io/document_surface.hpp"

#include "core/mesh/normal_rotations.hpp"

namespace meshmark {

WeldedSurface document_surface(const MeshDocument& document) {
  Mesh scene = document.scene();
  return document.scene_welded() ? already_welded(std::move(scene)) : weld_positions(scene.V, scene.F);
}

Mesh read_surface(const std::filesystem::path& path, const ReadOptions& limits) {
  DocumentReadOptions options;
  options.limits = limits;
  return document_surface(*read_document_file(path, options)).mesh;
}

namespace {

// Slots that further instances repeat cannot take every instance's move: each takes the mean of
// them, brought into its own frame, so that every instance carries its share of the mark.
void share_instance_moves(const MeshDocument& document, const WeldedSurface& surface, const Vertices& surface_V,
                          Vertices& slots) {
  if (document.further_instances().empty()) return;
  const Vertices& original = document.slot_positions();
  Vertices sum = Vertices::Zero(original.rows(), 3);
  std::vector<int> count(static_cast<std::size_t>(original.rows()), 0);
  const auto add = [&](std::size_t scene_vertex, int slot, const Eigen::Matrix3d& to_slot) {
    const int w = surface.vertex_of[scene_vertex];
    if (w < 0) return;
    sum.row(slot) += (to_slot * (surface_V.row(w) - surface.mesh.V.row(w)).transpose()).transpose();
    ++count[static_cast<std::size_t>(slot)];
  };
  for (Eigen::Index slot = 0; slot < original.rows(); ++slot)
    add(static_cast<std::size_t>(slot), static_cast<int>(slot), Eigen::Matrix3d::Identity());
  std::size_t first = static_cast<std::size_t>(original.rows());
  std::vector<char> repeated(count.size(), 0);
  for (const FurtherInstance& instance : document.further_instances()) {
    const bool invertible = !instance.move_to_slot.isZero();  // a flattened instance says nothing
    for (std::size_t k = 0; k < instance.slots.size(); ++k) {
      repeated[static_cast<std::size_t>(instance.slots[k])] = 1;
      if (invertible) add(first + k, instance.slots[k], instance.move_to_slot);
    }
    first += instance.slots.size();
  }
  for (Eigen::Index slot = 0; slot < original.rows(); ++slot)
    if (repeated[static_cast<std::size_t>(slot)] && count[static_cast<std::size_t>(slot)] > 0)
      slots.row(slot) = original.row(slot) + sum.row(slot) / count[static_cast<std::size_t>(slot)];
}

}  // namespace

MovedSlots move_slots(const MeshDocument& document, const WeldedSurface& surface, const Vertices& surface_V) {
  MovedSlots out;
  out.positions = stored_positions(surface, surface_V, document.slot_positions());
  share_instance_moves(document, surface, surface_V, out.positions);
  if (!document.turns_directions()) return out;  // no rotations: nothing to turn
  const std::vector<Eigen::Quaterniond> turned = normal_rotations(surface.mesh.V, surface_V, surface.mesh.F);
  const auto slots = static_cast<std::size_t>(document.slot_positions().rows());  // the scene's first vertices
  out.rotations.assign(slots, Eigen::Quaterniond::Identity());
  for (std::size_t slot = 0; slot < slots; ++slot)
    if (surface.vertex_of[slot] >= 0) out.rotations[slot] = turned[static_cast<std::size_t>(surface.vertex_of[slot])];
  return out;
}

}  // namespace meshmark
