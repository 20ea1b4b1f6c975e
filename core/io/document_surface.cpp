#include "core/io/document_surface.hpp"

#include "core/mesh/normal_rotations.hpp"

namespace meshmark {

WeldedSurface document_surface(const MeshDocument& document) {
  return weld_positions(document.slot_positions(), document.slot_triangles());
}

Mesh read_surface(const std::filesystem::path& path, const ReadOptions& limits) {
  DocumentReadOptions options;
  options.limits = limits;
  return document_surface(*read_document_file(path, options)).mesh;
}

Mesh read_welded_scene(const std::filesystem::path& path, const ReadOptions& limits) {
  DocumentReadOptions options;
  options.limits = limits;
  const Mesh scene = read_document_file(path, options)->scene();
  return weld_positions(scene.V, scene.F).mesh;
}

std::optional<std::string> instancing_problem(const MeshDocument& document) {
  for (const DocumentPart& part : document.parts())
    if (part.instances > 1)
      return part.name + " is drawn " + std::to_string(part.instances) +
             " times (instanced): a marked copy's further instances would not read back yet, so it cannot be "
             "watermarked";
  return std::nullopt;
}

MovedSlots move_slots(const MeshDocument& document, const WeldedSurface& surface, const Vertices& surface_V) {
  MovedSlots out;
  out.positions = stored_positions(surface, surface_V, document.slot_positions());
  const std::vector<Eigen::Quaterniond> turned = normal_rotations(surface.mesh.V, surface_V, surface.mesh.F);
  out.rotations.assign(surface.vertex_of.size(), Eigen::Quaterniond::Identity());
  for (std::size_t slot = 0; slot < surface.vertex_of.size(); ++slot)
    if (surface.vertex_of[slot] >= 0) out.rotations[slot] = turned[static_cast<std::size_t>(surface.vertex_of[slot])];
  return out;
}

}  // namespace meshmark
