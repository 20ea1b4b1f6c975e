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
  return std::nullopt;
}

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
  if (auto format = parse_mesh_format(ext)) return *format;
  throw MeshIoError(path.string() + ": cannot tell the mesh format from the extension '" +
                    path.extension().string() + "' (expected .obj, .off, .ply or .stl)");
}

std::string to_string(MeshFormat format) {
  switch (format) {
    case MeshFormat::obj: return "obj";
    case MeshFormat::off: return "off";
    case MeshFormat::ply: return "ply";
    case MeshFormat::stl: return "stl";
  }
  return "unknown";
}

}  // namespace meshmark
