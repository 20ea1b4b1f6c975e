#pragma once
// Mesh file formats the core reads and writes.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace meshmark {

enum class MeshFormat { obj, off, ply, stl, glb, gltf, threemf };

/// "obj", "off", "ply", "stl", "glb", "gltf" or "3mf" (case-insensitive); nullopt otherwise.
std::optional<MeshFormat> parse_mesh_format(std::string_view name);

/// The format named by a path's extension; throws MeshIoError if it names none.
MeshFormat mesh_format_from_path(const std::filesystem::path& path);

/// Lower-case name of a format ("obj", ..., "3mf"): also its file extension.
std::string to_string(MeshFormat format);

/// The names, for messages: "obj, off, ply, stl, glb, gltf or 3mf".
std::string known_mesh_formats();

}  // namespace meshmark
