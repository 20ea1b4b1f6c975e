#pragma once
// The surface the pipeline validates, parameterizes and marks, out of a document's slots (stored
// vertices welded by position), and the slots again after the surface moved: every stored copy
// of a welded vertex at its new place (so seams stay closed), its normals and tangents turned as
// the surface's normal turned there.

#include <filesystem>
#include <optional>
#include <string>

#include "core/io/mesh_document.hpp"
#include "core/mesh/weld_positions.hpp"

namespace meshmark {

/// The document's slots welded by exact position (see weld_positions).
WeldedSurface document_surface(const MeshDocument& document);

/// The welded surface of the mesh file at `path`: what `embed` marks and `detect` compares with.
Mesh read_surface(const std::filesystem::path& path, const ReadOptions& limits = {});
/// Every instance of the file's scene, welded: what a suspect copy shows.
Mesh read_welded_scene(const std::filesystem::path& path, const ReadOptions& limits = {});

/// Why the document cannot be watermarked as it is, if it cannot: a mesh instanced more than once
/// is marked once (its slots are its first instance), and detection does not yet tell a further
/// instance in a suspect from the surface it lies near, so such a copy would not read back.
std::optional<std::string> instancing_problem(const MeshDocument& document);

struct MovedSlots {
  Vertices positions;         ///< #slots × 3
  NormalRotations rotations;  ///< one per slot
};

/// The slots after the surface (`surface`, from document_surface) moved to `surface_V`
/// (#surface vertices × 3). Slots no triangle uses stay where they were.
MovedSlots move_slots(const MeshDocument& document, const WeldedSurface& surface, const Vertices& surface_V);

}  // namespace meshmark
