#pragma once
// What differs between a file and its marked copy outside the bytes that may change: positions,
// the normals and tangents that follow them, and the records that describe them (accessor
// bounds, a quantized mesh's node shift, a Draco stream's length). Format by format, read with
// this test code's own simple parsing, not the documents':
//   glTF/GLB  the JSON but those members, and every buffer view no POSITION/NORMAL/TANGENT reads;
//   OBJ       every line but v and vn, in order, and the fields of v lines after x y z;
//   PLY       the header, and every property but x y z nx ny nz, of every element;
//   STL       the 80-byte header, the count and each facet's attribute bytes (binary);
//   3MF       every part but the model byte for byte, and the model with vertex values blanked.

#include <filesystem>
#include <string>

#include "core/io/mesh_format.hpp"

namespace meshmark::test {

/// The first difference outside positions between `original` and `marked` (main files of
/// `format`; glTF companions are read beside `original_path` and `marked_path`), or "" if none.
std::string difference_outside_positions(const std::filesystem::path& original_path,
                                         const std::filesystem::path& marked_path);
std::string difference_outside_positions(const std::string& original, const std::string& marked, MeshFormat format,
                                         const std::filesystem::path& original_folder = {},
                                         const std::filesystem::path& marked_folder = {});

}  // namespace meshmark::test
