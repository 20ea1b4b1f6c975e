#pragma once
// A mesh file as it was read, kept whole: its bytes, the positions and polygons the pipeline works
// on, and where every position (and every normal and tangent) is stored, so that new positions
// can be written back in the file's own format and encoding with nothing else changed.
//
// A document stores positions in "slots": one per stored vertex of the file (an OBJ `v` line, a
// PLY vertex, a glTF accessor element, an STL facet corner, a 3MF vertex). Slot positions are in
// world space (glTF and 3MF node and item transforms applied). An instanced glTF mesh or 3MF
// object has its slots once, placed by its first instance; its further instances repeat those
// slots elsewhere. The scene (every instance) is the surface that is marked and that a suspect
// shows; every instance moves alike, since they share their stored positions.
//
// Writing with unchanged positions reproduces the input byte for byte; with changed ones, only the
// bytes of changed positions (and of the normals and tangents that follow them, accessor bounds,
// STL facet normals) differ.

#include <Eigen/Geometry>
#include <filesystem>
#include <functional>
#include <map>
#include <utility>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/io/mesh_format.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/read_options.hpp"
#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Companion files one document may name (material libraries, textures, buffers).
inline constexpr std::size_t kMaxCompanions = 10'000;

/// Files by path relative to the main file's folder ("" is the main file itself).
using DocumentFiles = std::map<std::string, std::string>;

/// The files of a document whose main file alone is written: `bytes` moved in. A braced list would
/// copy them (an initializer list's elements are const), which at millions of vertices cost seconds.
inline DocumentFiles main_file_only(std::string bytes) {
  DocumentFiles files;
  files.emplace("", std::move(bytes));
  return files;
}

/// What `meshmark info` says about a part of a document (an OBJ group or material, a glTF
/// primitive, a 3MF object).
struct DocumentPart {
  std::string name;
  std::size_t stored_vertices = 0;
  std::size_t triangles = 0;
  std::size_t instances = 1;
  std::vector<std::string> attributes;  ///< e.g. "NORMAL:VEC3/f32", "vt", "red:uchar"
};

/// A further instance of an instanced mesh: the slots it repeats and where it puts them.
struct FurtherInstance {
  Mesh mesh;               ///< world space
  std::vector<int> slots;  ///< per vertex of `mesh`: the slot it repeats
  /// A move of this instance's vertex as the same move of its slot (the first instance's linear
  /// transform times the inverse of this one's); zero when this instance's is singular.
  Eigen::Matrix3d move_to_slot = Eigen::Matrix3d::Zero();
};

/// move_to_slot for an instance placed by `world` whose slots were placed by `slot_world`.
Eigen::Matrix3d move_to_slot(const Eigen::Matrix3d& slot_world, const Eigen::Matrix3d& world);

/// Per slot: the rotation that its normals and tangents take (the rotation the surface's own
/// normal made there).
using NormalRotations = std::vector<Eigen::Quaterniond>;

/// The name a changed companion file (a glTF buffer) takes, from its URI; unset: the same URI.
/// The main file refers to it by the new name.
using CompanionNames = std::function<std::string(const std::string& uri)>;

class MeshDocument {
 public:
  virtual ~MeshDocument() = default;

  MeshFormat format() const { return format_; }
  /// #slots × 3, world space.
  const Vertices& slot_positions() const { return positions_; }
  /// Triangles over slots (polygons fan-triangulated).
  const Faces& slot_triangles() const { return triangles_; }
  /// Every instance of every mesh, world space: the slots, then each further instance's vertices.
  /// What is marked, and what a leaked copy of this file shows.
  Mesh scene() const;
  const std::vector<FurtherInstance>& further_instances() const { return further_instances_; }
  std::size_t polygons_triangulated() const { return polygons_triangulated_; }
  /// The scene is one surface as it is: no two vertices at one position, every vertex on a
  /// triangle, no triangle collapsed or repeated (a reader that welded, as STL's does). Welding it
  /// again would change nothing.
  bool scene_welded() const { return scene_welded_; }
  virtual std::vector<DocumentPart> parts() const = 0;
  /// The files the main file refers to, by relative URI (glTF buffers and images; an OBJ's
  /// material libraries and their textures): what travels with it.
  const std::vector<std::string>& companions() const { return companions_; }

  /// The files after moving every slot to `positions` (world space, #slots × 3) and turning its
  /// normals and tangents by `rotations` (one per slot; empty: none). Slots whose position is
  /// unchanged keep their stored bytes. The result holds the main file ("") and the companions
  /// that changed, by their (new) names. Throws MeshIoError when the format cannot hold them.
  virtual DocumentFiles write(const Vertices& positions, const NormalRotations& rotations,
                              const CompanionNames& names = {}) const = 0;
  /// Whether write() turns stored directions (normals, tangents) by `rotations`; a document that
  /// stores none, or recomputes them (STL's facet normals), spares its caller computing them.
  virtual bool turns_directions() const { return true; }

 protected:
  explicit MeshDocument(MeshFormat format) : format_(format) {}
  std::vector<FurtherInstance> further_instances_;

  MeshFormat format_;
  Vertices positions_;
  Faces triangles_;
  std::size_t polygons_triangulated_ = 0;
  bool scene_welded_ = false;
  /// Takes a finished builder's mesh as the scene, without copying it (at millions of vertices,
  /// a hundred megabytes).
  void take_scene(ReadResult&& read) {
    positions_ = std::move(read.mesh.V);
    triangles_ = std::move(read.mesh.F);
    polygons_triangulated_ = read.polygons_triangulated;
  }
  std::vector<std::string> companions_;
  /// Adds a companion unless listed already; false if it was. MeshLimitError past kMaxCompanions
  /// (an OBJ line naming a million libraries must not cost a million searches of a list).
  bool add_companion(const std::string& uri, const std::string& source);

 private:
  std::set<std::string> companion_set_;
};

/// Limits and where companion files come from.
struct DocumentReadOptions {
  ReadOptions limits;
  /// A companion file (a glTF buffer) by its URI, relative to the main file: its bytes, or
  /// throws MeshIoError. Unset: companions cannot be read.
  std::function<std::string(const std::string& uri)> companion;
  /// False for a document that is only read (a copy read back): a reader may then keep none of
  /// what writing the file back needs, and write() throws std::logic_error. PLY and OBJ leave
  /// out their places (107 MB at 2.2M vertices) and let their bytes go once parsed.
  bool for_writing = true;
};

/// Reads a document from bytes in memory. `source` labels error messages. Throws MeshIoError.
std::unique_ptr<MeshDocument> read_document(std::string bytes, MeshFormat format,
                                            const DocumentReadOptions& options = {},
                                            const std::string& source = "mesh");
/// Reads a document from a file (format from the extension; companions beside it).
std::unique_ptr<MeshDocument> read_document_file(const std::filesystem::path& path, DocumentReadOptions options = {});

/// A relative URI as a path: %XX escapes decoded (glTF writes "my%20wood.png").
std::string percent_decoded(std::string_view uri);

/// A whole file's bytes; MeshIoError if it cannot be read, MeshLimitError above `max_bytes`.
std::string read_file_bytes(const std::filesystem::path& path, std::size_t max_bytes);

}  // namespace meshmark
