#pragma once
// Reading a mesh file as a plain mesh: the stored vertices (STL corners welded by position; every
// instance of a glTF scene or 3MF build) and their polygons, triangulated. The parsers are the
// documents' (core/io/mesh_document): our own, not OpenMesh's, pure functions of their input, so
// any number of threads may read at once, and they never trust a header's counts before
// allocating.
// Polygons with more than three vertices are fan-triangulated (and counted); faces with fewer
// than three vertices, or that repeat a vertex, are refused; so are files without a vertex or a
// face, and coordinates that are not finite or beyond ±kMaxCoordinate.

#include <cstddef>
#include <filesystem>
#include <string_view>

#include "core/io/mesh_format.hpp"
#include "core/io/mesh_io_error.hpp"
#include "core/io/read_options.hpp"
#include "core/mesh/mesh.hpp"

namespace meshmark {

struct ReadResult {
  Mesh mesh;
  std::size_t polygons_triangulated = 0;  ///< input faces with >3 vertices, fan-triangulated
};

/// Reads a mesh file; the format comes from the extension. Throws MeshIoError.
ReadResult read_mesh(const std::filesystem::path& path, const ReadOptions& options = {});

/// Reads a mesh from bytes in memory; `source_name` only labels error messages.
/// Throws MeshIoError.
ReadResult read_mesh_from_memory(std::string_view bytes, MeshFormat format, const ReadOptions& options = {},
                                 std::string_view source_name = "mesh");

}  // namespace meshmark
