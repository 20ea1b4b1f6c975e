#pragma once
// Reading OBJ, OFF, PLY (ASCII, binary little and big endian) and STL (ASCII and binary).
//
// Our own parsers, not OpenMesh's: they are pure functions of their input, so any number of
// threads may read at once, and they never trust a header's counts before allocating.
// Polygons with more than three vertices are fan-triangulated (and counted); faces with fewer
// than three vertices, or that repeat a vertex, are refused; so are files without a vertex or a
// face, and coordinates that are not finite or beyond ±kMaxCoordinate.

#include <cstddef>
#include <filesystem>
#include <string_view>

#include "core/io/mesh_format.hpp"
#include "core/io/mesh_io_error.hpp"
#include "core/mesh/mesh.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

/// Limits that keep a hostile file from taking the machine down. Every reader's work is linear
/// (or n log n) in the file's size, whatever its header claims.
struct ReadOptions {
  std::size_t max_vertices = 50'000'000;       ///< refuse files with more vertices (MeshLimitError)
  std::size_t max_faces = 100'000'000;         ///< refuse files with more (triangulated) faces (MeshLimitError)
  std::size_t max_file_bytes = 4ull << 30;     ///< refuse larger files (read_mesh from a path)
  const JobControl* control = nullptr;         ///< polled while reading: a time limit or a cancel stops it
};

/// Coordinates beyond this magnitude are refused: the pipeline multiplies coordinates (areas,
/// normals, squared distances), and must stay far from overflow.
inline constexpr double kMaxCoordinate = 1e30;

struct ReadResult {
  Mesh mesh;
  std::size_t polygons_triangulated = 0;  ///< input faces with >3 vertices, fan-triangulated
  std::size_t stl_corners_welded = 0;     ///< STL triangle corners merged into shared vertices
};

/// Reads a mesh file; the format comes from the extension. Throws MeshIoError.
ReadResult read_mesh(const std::filesystem::path& path, const ReadOptions& options = {});

/// Reads a mesh from bytes in memory; `source_name` only labels error messages.
/// Throws MeshIoError.
ReadResult read_mesh_from_memory(std::string_view bytes, MeshFormat format,
                                 const ReadOptions& options = {},
                                 std::string_view source_name = "mesh");

}  // namespace meshmark
