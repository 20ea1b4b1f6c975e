#include "core/io/read_mesh.hpp"

#include <fstream>
#include <string>

#include "core/io/readers.hpp"

namespace meshmark {

ReadResult read_mesh_from_memory(std::string_view bytes, MeshFormat format, const ReadOptions& options,
                                 std::string_view source_name) {
  switch (format) {
    case MeshFormat::obj: return read_obj(bytes, options, source_name);
    case MeshFormat::off: return read_off(bytes, options, source_name);
    case MeshFormat::ply: return read_ply(bytes, options, source_name);
    case MeshFormat::stl: return read_stl(bytes, options, source_name);
  }
  throw MeshIoError(std::string(source_name) + ": unknown mesh format");
}

ReadResult read_mesh(const std::filesystem::path& path, const ReadOptions& options) {
  const MeshFormat format = mesh_format_from_path(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshIoError(path.string() + ": cannot open the file for reading");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw MeshIoError(path.string() + ": cannot tell the file size: " + ec.message());
  if (size > options.max_file_bytes)
    throw MeshIoError(path.string() + ": the file is " + std::to_string(size) + " bytes, above the limit of " +
                      std::to_string(options.max_file_bytes));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size)))
    throw MeshIoError(path.string() + ": cannot read the file");
  return read_mesh_from_memory(bytes, format, options, path.string());
}

}  // namespace meshmark
