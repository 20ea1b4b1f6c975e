#pragma once
// What the web console draws: a mesh as a compact binary PLY (float positions, 32-bit indices)
// with, for a marked copy, each vertex's displacement from the original as a scalar.

#include <optional>
#include <string>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Binary little-endian PLY: `float x, y, z` per vertex, then `float displacement` when
/// `displacement` is given (one value per vertex), and `list uchar uint vertex_indices` per face.
std::string write_preview_ply(const Mesh& mesh, const std::optional<std::vector<float>>& displacement = std::nullopt);

/// Each vertex's move from `original` to `marked` (the same vertices, in the same order) along
/// the original's vertex normal, in percent of the original's bounding-box diagonal: the mark
/// lives in these offsets (tangential moves do not change the surface). Throws when the vertex
/// counts differ.
std::vector<float> normal_displacement_percent(const Mesh& original, const Vertices& marked);

}  // namespace meshmark
