#pragma once
// Writing OBJ, OFF, PLY and STL. Vertex order and faces are written exactly as given. Text
// coordinates keep 1e-7 of the bounding box diagonal (CoordinateText: a marked copy's file is
// not 40 % larger than its original for digits that carry nothing); binary PLY stores doubles,
// so its read → write → read is lossless. Binary STL can only hold 32-bit floats.

#include <filesystem>
#include <string>

#include "core/io/mesh_format.hpp"
#include "core/io/mesh_io_error.hpp"
#include "core/mesh/mesh.hpp"

namespace meshmark {

struct WriteOptions {
  bool binary = false;      ///< PLY and STL: binary instead of ASCII
  bool big_endian = false;  ///< binary PLY only
  /// Text coordinates as the shortest text that reads back to the same double: a lossless round
  /// trip (e.g. a parameterization on the sphere, whose smallest triangles are far below 1e-7).
  bool lossless_text = false;
};

/// Binary STL is refused (MeshIoError) when rounding to 32-bit floats would move a vertex by
/// more than this fraction of the bounding-box diagonal (a mesh far from the origin for its size).
inline constexpr double kMaxStlRounding = 1e-5;

/// Throws MeshIoError when binary STL's 32-bit floats cannot hold the coordinates of `mesh` (see
/// kMaxStlRounding).
void check_fits_float32(const Mesh& mesh);

/// The file's bytes, in memory.
std::string write_mesh_to_memory(const Mesh& mesh, MeshFormat format, const WriteOptions& options = {});

/// Writes to `path` (format from the extension) through a temporary file renamed into place,
/// so a reader never sees half a file. Throws MeshIoError.
void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const WriteOptions& options = {});

}  // namespace meshmark
