#include "core/io/mesh_format.hpp"

#include <algorithm>
#include <cctype>

#include "core/io/mesh_io_error.hpp"

namespace meshmark {

std::optional<MeshFormat> parse_mesh_format(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == "obj") return MeshFormat::obj;
  if (lower == "off") return MeshFormat::off;
  if (lower == "ply") return MeshFormat::ply;
  if (lower == "stl") return MeshFormat::stl;
  if (lower == "glb") return MeshFormat::glb;
  if (lower == "gltf") return MeshFormat::gltf;
  if (lower == "3mf") return MeshFormat::threemf;
  return std::nullopt;
}

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
  if (auto format = parse_mesh_format(ext)) return *format;
  throw MeshIoError(path.string() + ": cannot tell the mesh format from the extension '" + path.extension().string() +
                    "' (expected " + known_mesh_formats() + ")");
}

std::string to_string(MeshFormat format) {
  switch (format) {
    case MeshFormat::obj:
      return "obj";
    case MeshFormat::off:
      return "off";
    case MeshFormat::ply:
      return "ply";
    case MeshFormat::stl:
      return "stl";
    case MeshFormat::glb:
      return "glb";
    case MeshFormat::gltf:
      return "gltf";
    case MeshFormat::threemf:
      return "3mf";
  }
  return "unknown";
}

std::string known_mesh_formats() { return "obj, off, ply, stl, glb, gltf or 3mf"; }

}  // namespace meshmark
