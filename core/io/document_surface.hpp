#pragma once
// The surface the pipeline validates, parameterizes and marks, out of a document's slots (stored
// vertices welded by position), and the slots again after the surface moved: every stored copy
// of a welded vertex at its new place (so seams stay closed), its normals and tangents turned as
// the surface's normal turned there. An instanced mesh is part of the surface once per instance.

#include <filesystem>
#include <string>

#include "core/io/mesh_document.hpp"
#include "core/mesh/weld_positions.hpp"

namespace meshmark {

/// The document's scene (its slots, then every further instance) welded by exact position (see
/// weld_positions).
WeldedSurface document_surface(const MeshDocument& document);

/// The welded surface of the mesh file at `path` (document_surface): what `embed` marks and what
/// a suspect copy shows.
Mesh read_surface(const std::filesystem::path& path, const ReadOptions& limits = {});

struct MovedSlots {
  Vertices positions;         ///< #slots × 3
  NormalRotations rotations;  ///< one per slot; empty when the document turns no directions
};

/// The slots after the surface (`surface`, from document_surface) moved to `surface_V`
/// (#surface vertices × 3). Slots no triangle uses stay where they were; a slot that further
/// instances repeat moves by the mean of its instances' moves (in its own frame).
MovedSlots move_slots(const MeshDocument& document, const WeldedSurface& surface, const Vertices& surface_V);

}  // namespace meshmark
