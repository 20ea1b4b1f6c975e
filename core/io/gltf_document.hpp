#pragma once
// glTF 2.0 as a document: .glb, and .gltf with external or embedded (data URI) buffers. Every
// triangle primitive of the default scene is read in world space through the node hierarchy; an
// instanced mesh has its slots once (its first instance), the others are the scene's. Positions
// are written back into their own accessor, component type and layout (interleaved views, sparse
// accessors, KHR_mesh_quantization's integer types), with the accessor's min/max; NORMAL and
// TANGENT follow the surface's rotation; a KHR_draco_mesh_compression stream is decoded and
// encoded again with each attribute's quantization (the buffer views after it move, their offsets
// patched). The JSON text is edited in place, value by value: every other byte (materials,
// textures, animations, skins, morph targets, extensions, extras, formatting) stays as it was.
//
// The class is shared by its reader (gltf_read.cpp: container, buffers, accessors, the scene) and
// its writer (gltf_write.cpp); everything else reaches it through read_gltf_document.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/io/byte_edits.hpp"
#include "core/io/document_readers.hpp"
#include "core/io/draco_primitive.hpp"
#include "core/io/gltf_components.hpp"
#include "core/io/json_spans.hpp"
#include "core/io/mesh_builder.hpp"
#include "core/io/scene_budget.hpp"

namespace meshmark::gltf {

using Json = nlohmann::json;
using Matrix4 = Eigen::Matrix4d;

struct Buffer {
  std::string bytes;
  enum class Origin { glb_chunk, data_uri, file } origin = Origin::file;
  std::string uri;
};

// Where an accessor's elements live.
struct Layout {
  int buffer = -1;         // -1: no buffer view (zeros, unless sparse)
  std::size_t offset = 0;  // element 0's first byte in the buffer
  std::size_t stride = 0;
  int component_type = kFloat;
  bool normalized = false;
  int components = 3;
  std::size_t element = 12;  // bytes
  std::size_t count = 0;
  std::map<std::uint32_t, std::size_t> sparse;  // element → its value's byte in sparse_buffer
  int sparse_buffer = -1;
};

class GltfDocument : public MeshDocument {
 public:
  GltfDocument(std::string bytes, bool binary, const DocumentReadOptions& options, const std::string& source);

  std::vector<DocumentPart> parts() const override { return parts_; }

  DocumentFiles write(const Vertices& P, const NormalRotations& rotations, const CompanionNames& names) const override;

 private:
  [[noreturn]] void fail(const std::string& what) const { throw MeshIoError(source_ + ": " + what); }

  // GLB: header, then chunks; the JSON chunk first. A .gltf is all JSON.
  void split_container();

  void load_buffers(const DocumentReadOptions& options);

  // The array member's entry (a reference into json_, never into a temporary).
  const Json& item(const char* array, std::size_t index) const;

  std::size_t index_of(const Json& j, const char* key) const;

  // A member that must be a non-negative integer (below 2^48: byte counts and enums), or `fallback`
  // when absent. Numbers of another kind are refused before any conversion could overflow.
  std::size_t whole(const Json& j, const char* key, std::size_t fallback) const;

  // A JSON value that must be an index (a non-negative integer below 2^31).
  std::size_t as_index(const Json& v, const std::string& what) const;

  // The byte range of a buffer view, checked against its buffer.
  struct View {
    int buffer;
    std::size_t offset, length, stride;
  };
  View view_of(std::size_t index) const;

  Layout layout_of(std::size_t accessor) const;

  void read_sparse(std::size_t accessor, const Json& s, std::size_t element, Layout& l) const;

  std::size_t builder_limit() const { return 100'000'000; }

  // Element i of an accessor as doubles.
  Eigen::Vector4d element(const Layout& l, std::size_t i, const std::vector<Buffer>& buffers) const;

  // Where element i is written (the sparse value if it has one).
  unsigned char* element_place(const Layout& l, std::size_t i, std::vector<Buffer>& buffers) const;

  static Matrix4 node_matrix(const Json& node);

  // Nodes of the default scene (or every root), depth first, with their world matrices.
  void walk_scene();

  void visit(std::size_t index, const Matrix4& parent, std::vector<char>& visiting, int depth);

  struct Instance {
    Matrix4 world;                // where the first node draws the mesh
    std::vector<int> face_slots;  // its triangles' corners, as slots
    std::vector<int> slots;       // further instances' vertices: the slots they repeat (index_slots)
    Faces faces;                  // ... and their triangles over those
  };

  void add_mesh_instance(std::size_t mesh, const Matrix4& world);

  // A further node drawing a mesh: in the scene, a copy of its first instance's slots.
  void add_further_instance(Instance& first, const Matrix4& world);

  // The slots a mesh's triangles use, in order, and its triangles over them: once per mesh.
  static void index_slots(Instance& first);

  void add_primitive(std::size_t mesh, std::size_t p, const Json& primitive, const Matrix4& world,
                     std::vector<int>& face_slots);

  void add_slot(const Eigen::Vector3d& local, const Matrix4& world, const std::string& where);

  void add_triangles(const std::vector<std::uint32_t>& indices, int mode, std::size_t count, std::size_t first_slot,
                     const std::string& name, std::vector<int>& face_slots, DocumentPart& part);

  struct Chunk {
    std::uint32_t type;
    std::size_t offset, length;
  };
  struct PositionSource {
    std::size_t accessor;
    Matrix4 world;
    std::size_t first_slot;
    std::size_t mesh;
  };
  struct DracoSource {
    DracoPrimitive codec;
    std::size_t view;
    std::size_t accessor;
    int position_id;
    Matrix4 world;
    std::size_t first_slot;
  };
  struct Primitive {
    Matrix4 world;
    int position_source = -1, draco = -1, normal = -1, tangent = -1;
  };

  std::string aliasing_problem() const;
  void write_positions(const Vertices& P, std::vector<Buffer>& buffers, ByteEdits& json_edits) const;
  std::map<std::size_t, Eigen::Vector3d> mesh_shifts(const std::vector<std::vector<Eigen::Vector3d>>& targets) const;
  void shift_nodes(const std::map<std::size_t, Eigen::Vector3d>& shifts, ByteEdits& json_edits) const;
  void write_directions(const NormalRotations& rotations, std::vector<Buffer>& buffers, ByteEdits& json_edits) const;
  void update_bounds(std::size_t accessor, const std::vector<Buffer>& buffers, ByteEdits& edits) const;
  void write_draco(const Vertices& P, std::vector<Buffer>& buffers, ByteEdits& json_edits) const;
  void set_bounds(std::size_t accessor, const Eigen::Vector4d& lo, const Eigen::Vector4d& hi, int components, int type,
                  ByteEdits& edits) const;
  void set_member(const std::string& object, const std::string& key, std::uint64_t value, ByteEdits& edits) const;
  DocumentFiles assemble(const std::vector<Buffer>& buffers, const ByteEdits& json_edits,
                         const CompanionNames& names) const;

  std::string bytes_;
  bool binary_;
  std::string source_;
  const ReadOptions limits_;
  MeshBuilder builder_;
  SceneBudget scene_budget_;
  std::string json_text_;
  Json json_;
  std::optional<JsonSpans> spans_;
  std::vector<Chunk> chunks_;
  std::size_t glb_length_ = 0;
  std::vector<Buffer> buffers_;
  std::map<std::size_t, std::size_t> accessor_slots_;  // POSITION accessor → its first slot
  std::vector<PositionSource> position_sources_;
  std::vector<DracoSource> draco_;
  std::vector<Primitive> primitives_;
  std::map<std::size_t, Instance> first_instance_;
  std::vector<Eigen::Vector3d> slot_local_;                     // per slot: its position in mesh space
  std::map<std::size_t, std::vector<std::size_t>> mesh_nodes_;  // mesh → the nodes that place it
  std::vector<DocumentPart> parts_;
};

}  // namespace meshmark::gltf
