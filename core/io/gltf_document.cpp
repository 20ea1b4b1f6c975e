// glTF 2.0 as a document: .glb, and .gltf with external or embedded (data URI) buffers. Every
// triangle primitive of the default scene is read in world space through the node hierarchy; an
// instanced mesh has its slots once (its first instance), the others are the scene's. Positions
// are written back into their own accessor, component type and layout (interleaved views, sparse
// accessors, KHR_mesh_quantization's integer types), with the accessor's min/max; NORMAL and
// TANGENT follow the surface's rotation; a KHR_draco_mesh_compression stream is decoded and
// encoded again with each attribute's quantization (the buffer views after it move, their offsets
// patched). The JSON text is edited in place, value by value: every other byte (materials,
// textures, animations, skins, morph targets, extensions, extras, formatting) stays as it was.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <tuple>
#include <string>
#include <vector>

#include "core/io/base64.hpp"
#include "core/io/byte_edits.hpp"
#include "core/io/number_text.hpp"
#include "core/io/document_readers.hpp"
#include "core/io/draco_primitive.hpp"
#include "core/io/json_spans.hpp"
#include "core/io/mesh_builder.hpp"
#include "core/io/scene_budget.hpp"
#include "core/util/json_nesting_depth.hpp"

namespace meshmark {

namespace {

using Json = nlohmann::json;
using Matrix4 = Eigen::Matrix4d;

constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126;
constexpr std::uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

std::size_t component_bytes(int type) {
  switch (type) {
    case kByte:
    case kUByte:
      return 1;
    case kShort:
    case kUShort:
      return 2;
    case kUInt:
    case kFloat:
      return 4;
    default:
      return 0;
  }
}

std::string type_name(int type) {
  switch (type) {
    case kByte:
      return "i8";
    case kUByte:
      return "u8";
    case kShort:
      return "i16";
    case kUShort:
      return "u16";
    case kUInt:
      return "u32";
    case kFloat:
      return "f32";
    default:
      return "?";
  }
}

// Components of a vector or scalar type (0 for a matrix: never read as a vertex attribute here).
int components_of(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  return 0;
}

// Bytes of one element, 0 for an unknown type: a matrix (skins' inverse bind matrices) stores
// each column from a 4-byte boundary (glTF 2.0, "Data Alignment").
std::size_t element_bytes(const std::string& type, int component_type) {
  const std::size_t component = component_bytes(component_type);
  for (const std::size_t n : {2u, 3u, 4u})
    if (type == "MAT" + std::to_string(n)) return n * ((n * component + 3) / 4 * 4);
  return component * static_cast<std::size_t>(components_of(type));
}

// One component as stored → its value (glTF's normalization rules), and back.
double decode_component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case kFloat: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case kByte: {
      const double v = static_cast<std::int8_t>(p[0]);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUByte:
      return normalized ? p[0] / 255.0 : p[0];
    case kShort: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUShort: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case kUInt: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default:
      return 0;
  }
}

void encode_component(unsigned char* p, int type, bool normalized, double value) {
  const auto integer = [&](double scale, double lo, double hi) {
    const double r = std::nearbyint(normalized ? value * scale : value);
    return std::clamp(r, lo, hi);  // quantized positions at the edge of their range stay on it
  };
  switch (type) {
    case kFloat: {
      const float f = static_cast<float>(value);
      std::memcpy(p, &f, 4);
      break;
    }
    case kByte: {
      const auto v = static_cast<std::int8_t>(integer(127, -127, 127));
      std::memcpy(p, &v, 1);
      break;
    }
    case kUByte: {
      const auto v = static_cast<std::uint8_t>(integer(255, 0, 255));
      std::memcpy(p, &v, 1);
      break;
    }
    case kShort: {
      const auto v = static_cast<std::int16_t>(integer(32767, -32767, 32767));
      std::memcpy(p, &v, 2);
      break;
    }
    case kUShort: {
      const auto v = static_cast<std::uint16_t>(integer(65535, 0, 65535));
      std::memcpy(p, &v, 2);
      break;
    }
    case kUInt: {
      const auto v = static_cast<std::uint32_t>(integer(1, 0, 4294967295.0));
      std::memcpy(p, &v, 4);
      break;
    }
    default:
      break;
  }
}

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
  GltfDocument(std::string bytes, bool binary, const DocumentReadOptions& options, const std::string& source)
      : MeshDocument(binary ? MeshFormat::glb : MeshFormat::gltf),
        bytes_(std::move(bytes)),
        binary_(binary),
        source_(source),
        limits_(options.limits),
        builder_(options.limits, source),
        scene_budget_(options.limits, source) {
    split_container();
    const JsonShape shape = json_shape(json_text_);
    if (shape.depth > 64) fail("the JSON nests deeper than 64 levels");
    if (shape.values > kMaxGltfJsonValues)  // the parsed tree costs ~100 bytes per value
      throw MeshLimitError(source_ + ": the JSON holds more than " + std::to_string(kMaxGltfJsonValues) + " values");
    json_ = Json::parse(json_text_, nullptr, false);
    if (json_.is_discarded() || !json_.is_object()) fail("the JSON part is not a JSON object");
    spans_.emplace(json_text_);
    const std::string version = json_.value("/asset/version"_json_pointer, std::string());
    if (version.rfind("2", 0) != 0) fail("only glTF 2.0 is read (asset.version is '" + version.substr(0, 10) + "')");
    load_buffers(options);
    for (const Json& image : json_.value("images", Json::array()))
      if (image.is_object() && image.contains("uri") && image["uri"].is_string() &&
          image["uri"].get<std::string>().rfind("data:", 0) != 0)
        add_companion(image["uri"].get<std::string>(), source_);
    walk_scene();
    if (builder_.face_count() == 0) fail("the scene has no triangle primitive");
    const ReadResult r = builder_.finish();
    positions_ = r.mesh.V;
    triangles_ = r.mesh.F;
  }

  std::vector<DocumentPart> parts() const override { return parts_; }

  DocumentFiles write(const Vertices& P, const NormalRotations& rotations, const CompanionNames& names) const override;

 private:
  [[noreturn]] void fail(const std::string& what) const { throw MeshIoError(source_ + ": " + what); }

  // GLB: header, then chunks; the JSON chunk first. A .gltf is all JSON.
  void split_container() {
    if (!binary_) {
      json_text_ = bytes_;
      return;
    }
    if (bytes_.size() < 20) fail("too short for a GLB file");
    std::uint32_t magic, version, length;
    std::memcpy(&magic, bytes_.data(), 4);
    std::memcpy(&version, bytes_.data() + 4, 4);
    std::memcpy(&length, bytes_.data() + 8, 4);
    if (magic != kGlbMagic) fail("not a GLB file (no 'glTF' magic)");
    if (version != 2) fail("GLB version " + std::to_string(version) + "; only 2 is read");
    if (length > bytes_.size())
      fail("the GLB header claims " + std::to_string(length) + " bytes; the file has " + std::to_string(bytes_.size()));
    std::size_t at = 12;
    while (at + 8 <= length) {
      std::uint32_t chunk_length, type;
      std::memcpy(&chunk_length, bytes_.data() + at, 4);
      std::memcpy(&type, bytes_.data() + at + 4, 4);
      if (chunk_length > length - at - 8) fail("a GLB chunk runs past the end of the file");
      chunks_.push_back({type, at + 8, chunk_length});
      at += 8 + chunk_length;
    }
    if (chunks_.empty() || chunks_[0].type != kJsonChunk) fail("the GLB file does not start with a JSON chunk");
    json_text_ = bytes_.substr(chunks_[0].offset, chunks_[0].length);
    while (!json_text_.empty() && (json_text_.back() == ' ' || json_text_.back() == '\0'))
      json_text_.pop_back();  // padding
    glb_length_ = length;
  }

  void load_buffers(const DocumentReadOptions& options) {
    const Json& buffers = json_.value("buffers", Json::array());
    std::map<std::string, std::size_t> files;  // uri → the buffer that names it
    for (std::size_t i = 0; i < buffers.size(); ++i) {
      Buffer b;
      const Json& j = buffers[i];
      if (!j.is_object()) fail("buffer " + std::to_string(i) + " is not an object");
      if (!j.contains("uri")) {
        if (!binary_ || i != 0) fail("buffer " + std::to_string(i) + " has no uri");
        const Chunk* bin = nullptr;
        for (const Chunk& c : chunks_)
          if (c.type == kBinChunk) bin = &c;
        if (!bin) fail("buffer 0 is the GLB's binary chunk, but the file has none");
        b.origin = Buffer::Origin::glb_chunk;
        b.bytes = bytes_.substr(bin->offset, bin->length);
      } else {
        b.uri = j.at("uri").get<std::string>();
        if (b.uri.rfind("data:", 0) == 0) {
          const std::size_t comma = b.uri.find(',');
          if (comma == std::string::npos || b.uri.substr(0, comma).find(";base64") == std::string::npos)
            fail("buffer " + std::to_string(i) + ": only base64 data URIs are read");
          auto decoded = base64_decode(std::string_view(b.uri).substr(comma + 1));
          if (!decoded) fail("buffer " + std::to_string(i) + ": its data URI is not base64");
          b.bytes = std::move(*decoded);
          b.origin = Buffer::Origin::data_uri;
        } else {
          if (!options.companion)
            fail("buffer " + std::to_string(i) + " is the file '" + b.uri + "', which cannot be read here");
          // Read once per buffer, each written back on its own: one file named twice would be
          // held twice and written back with only one buffer's changes.
          if (const auto [it, fresh] = files.emplace(b.uri, i); !fresh)
            fail("buffers " + std::to_string(it->second) + " and " + std::to_string(i) + " both name the file '" +
                 b.uri + "'; each buffer must be a file of its own");
          b.bytes = options.companion(b.uri);
          b.origin = Buffer::Origin::file;
          add_companion(b.uri, source_);
        }
      }
      if (!j.contains("byteLength")) fail("buffer " + std::to_string(i) + " has no 'byteLength'");
      const auto declared = whole(j, "byteLength", 0);
      if (declared > b.bytes.size())
        fail("buffer " + std::to_string(i) + " declares " + std::to_string(declared) + " bytes but holds " +
             std::to_string(b.bytes.size()));
      buffers_.push_back(std::move(b));
    }
  }

  // The array member's entry (a reference into json_, never into a temporary).
  const Json& item(const char* array, std::size_t index) const {
    const auto it = json_.find(array);
    if (it == json_.end() || !it->is_array() || index >= it->size() || !(*it)[index].is_object())
      fail(std::string("no ") + array + " entry " + std::to_string(index));
    return (*it)[index];
  }

  std::size_t index_of(const Json& j, const char* key) const {
    return as_index(j.at(key), std::string("'") + key + "'");
  }

  // A member that must be a non-negative integer (below 2^48: byte counts and enums), or `fallback`
  // when absent. Numbers of another kind are refused before any conversion could overflow.
  std::size_t whole(const Json& j, const char* key, std::size_t fallback) const {
    const auto it = j.find(key);
    if (it == j.end()) return fallback;
    if (!it->is_number_unsigned() || it->get<std::uint64_t>() > (std::uint64_t{1} << 48))
      fail(std::string("'") + key + "' must be a non-negative integer");
    return it->get<std::size_t>();
  }

  // A JSON value that must be an index (a non-negative integer below 2^31).
  std::size_t as_index(const Json& v, const std::string& what) const {
    if (!v.is_number_unsigned() || v.get<std::uint64_t>() > 0x7fffffffu) fail(what + " must be an index");
    return v.get<std::size_t>();
  }

  // The byte range of a buffer view, checked against its buffer.
  struct View {
    int buffer;
    std::size_t offset, length, stride;
  };
  View view_of(std::size_t index) const {
    const Json& v = item("bufferViews", index);
    View view{static_cast<int>(index_of(v, "buffer")), whole(v, "byteOffset", 0), whole(v, "byteLength", 0),
              whole(v, "byteStride", 0)};
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= buffers_.size())
      fail("buffer view " + std::to_string(index) + " names no buffer");
    if (view.offset > buffers_[static_cast<std::size_t>(view.buffer)].bytes.size() ||
        view.length > buffers_[static_cast<std::size_t>(view.buffer)].bytes.size() - view.offset)
      fail("buffer view " + std::to_string(index) + " runs past the end of its buffer");
    return view;
  }

  Layout layout_of(std::size_t accessor) const {
    const Json& a = item("accessors", accessor);
    Layout l;
    l.component_type = static_cast<int>(whole(a, "componentType", 0));
    l.normalized = a.value("normalized", false);
    l.components = components_of(a.value("type", std::string()));
    l.element = element_bytes(a.value("type", std::string()), l.component_type);
    l.count = whole(a, "count", 0);
    const std::size_t element = l.element;
    if (element == 0) fail("accessor " + std::to_string(accessor) + " has an unknown component type or type");
    if (l.count > builder_limit())
      fail("accessor " + std::to_string(accessor) + " has more elements than the limit for one mesh");
    if (a.contains("bufferView")) {
      const View v = view_of(index_of(a, "bufferView"));
      l.buffer = v.buffer;
      l.stride = v.stride ? v.stride : element;
      const std::size_t start = whole(a, "byteOffset", 0);
      if (l.stride < element)
        fail("accessor " + std::to_string(accessor) + ": its view's stride is shorter than an element");
      if (l.count > 0 &&
          (start > v.length || (l.count - 1) > (v.length - start - std::min(v.length - start, element)) / l.stride ||
           start + (l.count - 1) * l.stride + element > v.length))
        fail("accessor " + std::to_string(accessor) + " runs past the end of its buffer view");
      l.offset = v.offset + start;
    }
    if (a.contains("sparse")) read_sparse(accessor, a.at("sparse"), element, l);
    return l;
  }

  void read_sparse(std::size_t accessor, const Json& s, std::size_t element, Layout& l) const {
    const std::size_t count = whole(s, "count", 0);
    const Json& indices = s.at("indices");
    const Json& values = s.at("values");
    const View iv = view_of(index_of(indices, "bufferView")), vv = view_of(index_of(values, "bufferView"));
    const int index_type = static_cast<int>(whole(indices, "componentType", 0));
    if (index_type != kUByte && index_type != kUShort && index_type != kUInt)
      fail("accessor " + std::to_string(accessor) + ": its sparse indices must be unsigned integers");
    const std::size_t ib = component_bytes(index_type);
    const std::size_t i0 = iv.offset + whole(indices, "byteOffset", 0), v0 = vv.offset + whole(values, "byteOffset", 0);
    if (ib == 0 || count > iv.length / ib || count > vv.length / element || i0 + count * ib > iv.offset + iv.length ||
        v0 + count * element > vv.offset + vv.length)
      fail("accessor " + std::to_string(accessor) + ": its sparse part runs past its buffer views");
    const std::string& ibytes = buffers_[static_cast<std::size_t>(iv.buffer)].bytes;
    for (std::size_t k = 0; k < count; ++k) {
      const auto index = static_cast<std::uint32_t>(
          decode_component(reinterpret_cast<const unsigned char*>(ibytes.data()) + i0 + k * ib, index_type, false));
      if (index >= l.count) fail("accessor " + std::to_string(accessor) + ": a sparse index beyond its count");
      l.sparse[index] = v0 + k * element;
    }
    l.sparse_buffer = vv.buffer;
  }

  std::size_t builder_limit() const { return 100'000'000; }

  // Element i of an accessor as doubles.
  Eigen::Vector4d element(const Layout& l, std::size_t i, const std::vector<Buffer>& buffers) const {
    Eigen::Vector4d v = Eigen::Vector4d::Zero();
    const unsigned char* p = nullptr;
    if (const auto s = l.sparse.find(static_cast<std::uint32_t>(i)); s != l.sparse.end())
      p = reinterpret_cast<const unsigned char*>(buffers[static_cast<std::size_t>(l.sparse_buffer)].bytes.data()) +
          s->second;
    else if (l.buffer >= 0)
      p = reinterpret_cast<const unsigned char*>(buffers[static_cast<std::size_t>(l.buffer)].bytes.data()) + l.offset +
          i * l.stride;
    if (!p) return v;
    for (int k = 0; k < l.components; ++k)
      v[k] = decode_component(p + k * component_bytes(l.component_type), l.component_type, l.normalized);
    return v;
  }

  // Where element i is written (the sparse value if it has one).
  unsigned char* element_place(const Layout& l, std::size_t i, std::vector<Buffer>& buffers) const {
    if (const auto s = l.sparse.find(static_cast<std::uint32_t>(i)); s != l.sparse.end())
      return reinterpret_cast<unsigned char*>(buffers[static_cast<std::size_t>(l.sparse_buffer)].bytes.data()) +
             s->second;
    if (l.buffer < 0) return nullptr;
    return reinterpret_cast<unsigned char*>(buffers[static_cast<std::size_t>(l.buffer)].bytes.data()) + l.offset +
           i * l.stride;
  }

  static Matrix4 node_matrix(const Json& node) {
    Matrix4 m = Matrix4::Identity();
    if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          m(r, c) = node["matrix"][static_cast<std::size_t>(4 * c + r)].get<double>();  // column-major
      return m;
    }
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    if (node.contains("translation")) {
      const Json& v = node["translation"];
      t.translate(Eigen::Vector3d(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()));
    }
    if (node.contains("rotation")) {
      const Json& q = node["rotation"];
      t.rotate(
          Eigen::Quaterniond(q.at(3).get<double>(), q.at(0).get<double>(), q.at(1).get<double>(), q.at(2).get<double>())
              .normalized());
    }
    if (node.contains("scale")) {
      const Json& s = node["scale"];
      t.scale(Eigen::Vector3d(s.at(0).get<double>(), s.at(1).get<double>(), s.at(2).get<double>()));
    }
    return t.matrix();
  }

  // Nodes of the default scene (or every root), depth first, with their world matrices.
  void walk_scene() {
    const Json& nodes = json_.value("nodes", Json::array());
    std::vector<std::size_t> roots;
    const Json& scenes = json_.value("scenes", Json::array());
    if (!scenes.empty()) {
      const std::size_t scene = whole(json_, "scene", 0);
      if (scene >= scenes.size()) fail("the default scene " + std::to_string(scene) + " does not exist");
      for (const Json& n : scenes[scene].value("nodes", Json::array())) roots.push_back(as_index(n, "a scene node"));
    } else {
      std::vector<char> child(nodes.size(), 0);
      for (const Json& n : nodes)
        for (const Json& c : n.value("children", Json::array()))
          if (c.is_number_unsigned() && c.get<std::size_t>() < nodes.size()) child[c.get<std::size_t>()] = 1;
      for (std::size_t i = 0; i < nodes.size(); ++i)
        if (!child[i]) roots.push_back(i);
    }
    std::vector<char> visiting(nodes.size(), 0);
    for (const std::size_t r : roots) visit(r, Matrix4::Identity(), visiting, 0);
  }

  void visit(std::size_t index, const Matrix4& parent, std::vector<char>& visiting, int depth) {
    if (index >= visiting.size()) fail("node " + std::to_string(index) + " does not exist");
    if (visiting[index] || depth > 256) fail("the node hierarchy has a cycle at node " + std::to_string(index));
    visiting[index] = 1;
    scene_budget_.visit();
    const Json& node = item("nodes", index);
    const Matrix4 world = parent * node_matrix(node);
    if (!world.allFinite()) fail("node " + std::to_string(index) + " has a transform that is not finite");
    if (node.contains("mesh")) {
      const std::size_t mesh = index_of(node, "mesh");
      mesh_nodes_[mesh].push_back(index);
      add_mesh_instance(mesh, world);
    }
    for (const Json& c : node.value("children", Json::array()))
      visit(as_index(c, "a child node"), world, visiting, depth + 1);
    visiting[index] = 0;
  }

  struct Instance {
    Matrix4 world;                // where the first node draws the mesh
    std::vector<int> face_slots;  // its triangles' corners, as slots
    std::vector<int> slots;       // further instances' vertices: the slots they repeat (index_slots)
    Faces faces;                  // ... and their triangles over those
  };

  void add_mesh_instance(std::size_t mesh, const Matrix4& world) {
    const Json& m = item("meshes", mesh);
    if (auto seen = first_instance_.find(mesh); seen != first_instance_.end()) {
      add_further_instance(seen->second, world);
      for (DocumentPart& p : parts_)
        if (p.name.rfind("mesh " + std::to_string(mesh) + " ", 0) == 0) ++p.instances;
      return;
    }
    Instance& instance = first_instance_[mesh];
    instance.world = world;
    const Json& primitives = m.value("primitives", Json::array());
    for (std::size_t p = 0; p < primitives.size(); ++p)
      add_primitive(mesh, p, primitives[p], world, instance.face_slots);
  }

  // A further node drawing a mesh: in the scene, a copy of its first instance's slots.
  void add_further_instance(Instance& first, const Matrix4& world) {
    if (first.slots.empty()) index_slots(first);
    scene_budget_.add_instance(first.slots.size(), first.faces.rows());
    FurtherInstance instance;
    instance.slots = first.slots;
    instance.mesh.F = first.faces;
    const auto n = static_cast<Eigen::Index>(instance.slots.size());
    instance.mesh.V.resize(n, 3);
    for (Eigen::Index v = 0; v < n; ++v)
      instance.mesh.V.row(v) =
          (world * slot_local_[static_cast<std::size_t>(instance.slots[static_cast<std::size_t>(v)])].homogeneous())
              .head<3>()
              .transpose();
    instance.move_to_slot = move_to_slot(first.world.topLeftCorner<3, 3>(), world.topLeftCorner<3, 3>());
    further_instances_.push_back(std::move(instance));
  }

  // The slots a mesh's triangles use, in order, and its triangles over them: once per mesh.
  static void index_slots(Instance& first) {
    std::map<int, int> vertex_of_slot;
    std::vector<int> faces;
    for (const int slot : first.face_slots) {
      const auto [at, added] = vertex_of_slot.emplace(slot, static_cast<int>(first.slots.size()));
      if (added) first.slots.push_back(slot);
      faces.push_back(at->second);
    }
    first.faces = Eigen::Map<const Faces>(faces.data(), static_cast<Eigen::Index>(faces.size() / 3), 3);
  }

  void add_primitive(std::size_t mesh, std::size_t p, const Json& primitive, const Matrix4& world,
                     std::vector<int>& face_slots) {
    const std::string name = "mesh " + std::to_string(mesh) + " primitive " + std::to_string(p);
    const int mode = static_cast<int>(whole(primitive, "mode", 4));
    DocumentPart part;
    part.name = name;
    const Json& attributes = primitive.value("attributes", Json::object());
    for (const auto& [attr, accessor] : attributes.items()) {
      const Json& a = item("accessors", as_index(accessor, "attribute " + attr));
      part.attributes.push_back(attr + ":" + a.value("type", std::string("?")) + "/" +
                                type_name(static_cast<int>(whole(a, "componentType", 0))) +
                                (a.value("normalized", false) ? "n" : ""));
    }
    if (primitive.contains("targets"))
      part.attributes.push_back("morph targets ×" + std::to_string(primitive["targets"].size()));
    if (mode < 4 || mode > 6 || !attributes.contains("POSITION")) {
      part.attributes.push_back("not triangles (mode " + std::to_string(mode) + "): left out");
      parts_.push_back(part);
      return;
    }
    Primitive record;
    record.world = world;
    record.normal = attributes.contains("NORMAL") ? static_cast<int>(as_index(attributes["NORMAL"], "NORMAL")) : -1;
    record.tangent = attributes.contains("TANGENT") ? static_cast<int>(as_index(attributes["TANGENT"], "TANGENT")) : -1;
    const std::size_t position_accessor = as_index(attributes["POSITION"], "POSITION");
    std::vector<std::uint32_t> indices;
    std::size_t count = 0;
    std::size_t first_slot = 0;
    const Json* draco = primitive.contains("extensions") ? &primitive["extensions"] : nullptr;
    if (draco && draco->contains("KHR_draco_mesh_compression")) {
      const Json& ext = (*draco)["KHR_draco_mesh_compression"];
      const std::size_t view_index = index_of(ext, "bufferView");
      const View v = view_of(view_index);
      const int id = static_cast<int>(as_index(ext.at("attributes").at("POSITION"), "the Draco POSITION attribute"));
      DracoSource source{
          DracoPrimitive(
              std::string_view(buffers_[static_cast<std::size_t>(v.buffer)].bytes).substr(v.offset, v.length), id,
              {limits_.max_vertices - std::min(limits_.max_vertices, builder_.vertex_count()), limits_.max_faces}),
          view_index,
          position_accessor,
          id,
          world,
          builder_.vertex_count()};
      const DracoPrimitive& d = source.codec;
      first_slot = source.first_slot;
      count = static_cast<std::size_t>(d.positions().rows());
      for (Eigen::Index i = 0; i < d.positions().rows(); ++i) add_slot(d.positions().row(i).transpose(), world, name);
      for (Eigen::Index f = 0; f < d.faces().rows(); ++f)
        for (int k = 0; k < 3; ++k) indices.push_back(static_cast<std::uint32_t>(d.faces()(f, k)));
      record.draco = static_cast<int>(draco_.size());
      part.attributes.push_back("KHR_draco_mesh_compression, positions at " + std::to_string(d.position_bits()) +
                                " bits");
      draco_.push_back(std::move(source));
    } else {
      const Layout l = layout_of(position_accessor);
      if (l.components != 3) fail(name + ": POSITION is not VEC3");
      count = l.count;
      if (auto seen = accessor_slots_.find(position_accessor); seen != accessor_slots_.end()) {
        first_slot = seen->second;  // primitives sharing a POSITION accessor share its slots
      } else {
        first_slot = builder_.vertex_count();
        accessor_slots_[position_accessor] = first_slot;
        position_sources_.push_back({position_accessor, world, first_slot, mesh});
        for (std::size_t i = 0; i < l.count; ++i) add_slot(element(l, i, buffers_).head<3>(), world, name);
      }
      record.position_source = static_cast<int>(position_sources_.size()) - 1;
      for (std::size_t s = 0; s < position_sources_.size(); ++s)
        if (position_sources_[s].accessor == position_accessor) record.position_source = static_cast<int>(s);
      if (primitive.contains("indices")) {
        const Layout il = layout_of(as_index(primitive["indices"], "indices"));
        if (il.components != 1 ||
            (il.component_type != kUByte && il.component_type != kUShort && il.component_type != kUInt))
          fail(name + ": indices must be unsigned scalars");
        indices.reserve(il.count);
        for (std::size_t i = 0; i < il.count; ++i)
          indices.push_back(static_cast<std::uint32_t>(element(il, i, buffers_)[0]));
      } else {
        for (std::size_t i = 0; i < count; ++i) indices.push_back(static_cast<std::uint32_t>(i));
      }
    }
    add_triangles(indices, mode, count, first_slot, name, face_slots, part);
    part.stored_vertices = count;
    parts_.push_back(part);
    primitives_.push_back(record);
  }

  void add_slot(const Eigen::Vector3d& local, const Matrix4& world, const std::string& where) {
    const Eigen::Vector3d w = (world * local.homogeneous()).head<3>();
    builder_.add_vertex(w.x(), w.y(), w.z(), where);
    slot_local_.push_back(local);
  }

  void add_triangles(const std::vector<std::uint32_t>& indices, int mode, std::size_t count, std::size_t first_slot,
                     const std::string& name, std::vector<int>& face_slots, DocumentPart& part) {
    const auto triangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (a >= count || b >= count || c >= count)
        fail(name + ": an index beyond its " + std::to_string(count) + " vertices");
      if (a == b || b == c || a == c) return;  // degenerate (strips use these to turn): not a face
      const long long corners[3] = {static_cast<long long>(first_slot + a), static_cast<long long>(first_slot + b),
                                    static_cast<long long>(first_slot + c)};
      builder_.add_polygon(corners, 3, name);
      face_slots.insert(face_slots.end(),
                        {static_cast<int>(corners[0]), static_cast<int>(corners[1]), static_cast<int>(corners[2])});
      ++part.triangles;
    };
    if (mode == 4)
      for (std::size_t i = 0; i + 2 < indices.size(); i += 3) triangle(indices[i], indices[i + 1], indices[i + 2]);
    else if (mode == 5)
      for (std::size_t i = 0; i + 2 < indices.size(); ++i)
        i % 2 ? triangle(indices[i + 1], indices[i], indices[i + 2])
              : triangle(indices[i], indices[i + 1], indices[i + 2]);
    else
      for (std::size_t i = 1; i + 1 < indices.size(); ++i) triangle(indices[0], indices[i], indices[i + 1]);
  }

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

void GltfDocument::set_bounds(std::size_t accessor, const Eigen::Vector4d& lo, const Eigen::Vector4d& hi,
                              int components, int type, ByteEdits& edits) const {
  const auto text = [&](const Eigen::Vector4d& v) {
    std::string s = "[";
    for (int k = 0; k < components; ++k) {
      if (k) s += ",";
      s += type == kFloat ? number_text(static_cast<float>(v[k])) : std::to_string(static_cast<long long>(v[k]));
    }
    return s + "]";
  };
  const std::string base = "/accessors/" + std::to_string(accessor);
  for (const auto& [key, value] : {std::pair{std::string("min"), lo}, std::pair{std::string("max"), hi}}) {
    if (spans_->has(base + "/" + key)) edits.replace(spans_->value(base + "/" + key), text(value));
    else {
      const std::size_t at = spans_->object_start(base);
      edits.replace({at, at}, "\"" + key + "\":" + text(value) + ",");
    }
  }
}

void GltfDocument::set_member(const std::string& object, const std::string& key, std::uint64_t value,
                              ByteEdits& edits) const {
  if (spans_->has(object + "/" + key)) {
    edits.replace(spans_->value(object + "/" + key), std::to_string(value));
  } else {
    const std::size_t at = spans_->object_start(object);
    edits.replace({at, at}, "\"" + key + "\":" + std::to_string(value) + ",");
  }
}

// The bytes that writing may change (every element of the POSITION, NORMAL and TANGENT accessors
// of the slots) must hold nothing else: not two of those accessors at once, not another accessor's
// element, sparse indices or a view no accessor describes (images, Draco streams). Files built
// otherwise (overlapping views) cannot be marked without changing more than positions.
std::string GltfDocument::aliasing_problem() const {
  struct Span {
    int buffer;
    std::size_t begin, end;
    long owner;
  };
  std::set<std::size_t> written;
  for (const PositionSource& s : position_sources_) written.insert(s.accessor);
  for (const Primitive& p : primitives_)
    if (p.position_source >= 0)
      for (const int a : {p.normal, p.tangent})
        if (a >= 0) written.insert(static_cast<std::size_t>(a));
  std::vector<Span> mine, others;
  std::set<std::size_t> described;  // views some accessor reads
  const Json& accessors = json_.value("accessors", Json::array());
  for (std::size_t a = 0; a < accessors.size(); ++a) {
    const Layout l = layout_of(a);
    const std::size_t size = l.element;
    std::vector<Span>& into = written.count(a) ? mine : others;
    const long owner = written.count(a) ? static_cast<long>(a) : -1;
    if (accessors[a].contains("bufferView")) described.insert(index_of(accessors[a], "bufferView"));
    for (std::size_t i = 0; i < l.count; ++i) {
      if (const auto sp = l.sparse.find(static_cast<std::uint32_t>(i)); sp != l.sparse.end())
        into.push_back({l.sparse_buffer, sp->second, sp->second + size, owner});
      else if (l.buffer >= 0)
        into.push_back({l.buffer, l.offset + i * l.stride, l.offset + i * l.stride + size, owner});
    }
    if (accessors[a].contains("sparse")) {
      const Json& sparse = accessors[a]["sparse"];
      for (const char* part : {"indices", "values"}) {
        const std::size_t v = index_of(sparse.at(part), "bufferView");
        described.insert(v);
        const View view = view_of(v);
        if (std::string(part) == "indices") others.push_back({view.buffer, view.offset, view.offset + view.length, -1});
      }
    }
  }
  const Json& views = json_.value("bufferViews", Json::array());
  for (std::size_t v = 0; v < views.size(); ++v)
    if (!described.count(v)) {
      const View view = view_of(v);
      others.push_back({view.buffer, view.offset, view.offset + view.length, -1});
    }
  const auto by_place = [](const Span& x, const Span& y) {
    return std::tie(x.buffer, x.begin) < std::tie(y.buffer, y.begin);
  };
  std::sort(mine.begin(), mine.end(), by_place);
  const std::string problem =
      "its positions, normals or tangents share bytes with other data (overlapping buffer views)";
  // Two written accessors overlapping: the latest-starting of any such pair meets a running end.
  std::vector<Span> merged;
  for (const Span& w : mine) {
    if (!merged.empty() && merged.back().buffer == w.buffer && w.begin < merged.back().end) {
      if (merged.back().owner != w.owner) return problem;
      if (w.end > merged.back().end) merged.back().end = w.end;
      continue;
    }
    merged.push_back(w);
  }
  for (const Span& o : others) {
    auto it = std::upper_bound(merged.begin(), merged.end(), o, by_place);
    if (it != merged.end() && it->buffer == o.buffer && it->begin < o.end) return problem;
    if (it != merged.begin() && std::prev(it)->buffer == o.buffer && std::prev(it)->end > o.begin) return problem;
  }
  return "";
}

// The range an integer component holds, in decoded units, and its step; floats: unbounded.
struct StoredRange {
  double lo, hi, step;
};
StoredRange stored_range(int type, bool normalized) {
  const double inf = std::numeric_limits<double>::infinity();
  switch (type) {
    case kByte:
      return normalized ? StoredRange{-1, 1, 1 / 127.0} : StoredRange{-127, 127, 1};
    case kUByte:
      return normalized ? StoredRange{0, 1, 1 / 255.0} : StoredRange{0, 255, 1};
    case kShort:
      return normalized ? StoredRange{-1, 1, 1 / 32767.0} : StoredRange{-32767, 32767, 1};
    case kUShort:
      return normalized ? StoredRange{0, 1, 1 / 65535.0} : StoredRange{0, 65535, 1};
    case kUInt:
      return {0, 4294967295.0, 1};
    default:
      return {-inf, inf, 0};
  }
}

// A direction of length `length` stored in three components: for normalized integers, the
// rounding (each component down or up) whose length is closest to `length`, then closest to the
// direction, so that unit normals and tangents stay unit within what the type can hold.
void encode_direction(unsigned char* p, int type, bool normalized, const Eigen::Vector3d& unit, double length) {
  const Eigen::Vector3d wanted = unit * length;
  const double step = normalized ? stored_range(type, true).step : 0.0;
  Eigen::Vector3d best = wanted;
  if (step > 0) {
    double best_cost = std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
      Eigen::Vector3d q;
      for (int k = 0; k < 3; ++k)
        q[k] = ((corner >> k) & 1 ? std::ceil(wanted[k] / step) : std::floor(wanted[k] / step)) * step;
      const double cost = 100 * std::pow(q.norm() - length, 2) + (q - wanted).squaredNorm();
      if (cost < best_cost) {
        best_cost = cost;
        best = q;
      }
    }
  }
  for (int k = 0; k < 3; ++k) encode_component(p + k * component_bytes(type), type, normalized, best[k]);
}

// The accessor's min and max over its elements as they are stored now (normalized integers in
// stored units, as glTF wants them).
void GltfDocument::update_bounds(std::size_t accessor, const std::vector<Buffer>& buffers, ByteEdits& edits) const {
  const Layout l = layout_of(accessor);
  Eigen::Vector4d lo = Eigen::Vector4d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < l.count; ++i) {
    Eigen::Vector4d e = element(l, i, buffers);
    if (l.normalized) e /= stored_range(l.component_type, true).step;
    lo = lo.cwiseMin(e);
    hi = hi.cwiseMax(e);
  }
  set_bounds(accessor, lo, hi, l.components, l.component_type, edits);
}

// Positions move in their accessors' mesh space. Integer (quantized) positions that would leave
// their type's range (gltfpack's start at 0) take the whole mesh along by a shift that its nodes
// take back (mesh_shifts, shift_nodes), so no position is clamped.
void GltfDocument::write_positions(const Vertices& P, std::vector<Buffer>& buffers, ByteEdits& json_edits) const {
  std::vector<std::vector<Eigen::Vector3d>> targets(position_sources_.size());
  std::vector<std::vector<char>> moved(position_sources_.size());
  for (std::size_t n = 0; n < position_sources_.size(); ++n) {
    const PositionSource& s = position_sources_[n];
    const Layout l = layout_of(s.accessor);
    const Matrix4 inverse = s.world.inverse();
    moved[n].assign(l.count, 0);
    for (std::size_t i = 0; i < l.count; ++i) {
      const auto slot = static_cast<Eigen::Index>(s.first_slot + i);
      if (P.row(slot) == positions_.row(slot) || !inverse.allFinite()) {
        targets[n].push_back(element(l, i, buffers_).head<3>());
      } else {
        targets[n].push_back((inverse * P.row(slot).transpose().homogeneous()).head<3>());
        moved[n][i] = 1;
      }
    }
  }
  const std::map<std::size_t, Eigen::Vector3d> shifts = mesh_shifts(targets);
  shift_nodes(shifts, json_edits);
  for (std::size_t n = 0; n < position_sources_.size(); ++n) {
    const PositionSource& s = position_sources_[n];
    const Layout l = layout_of(s.accessor);
    const auto shift = shifts.find(s.mesh);
    bool changed = false;
    for (std::size_t i = 0; i < l.count; ++i) {
      if (!moved[n][i] && shift == shifts.end()) continue;
      unsigned char* place = element_place(l, i, buffers);
      if (!place)
        throw MeshIoError(source_ + ": accessor " + std::to_string(s.accessor) + " has no storage for its element " +
                          std::to_string(i));
      const Eigen::Vector3d local = targets[n][i] + (shift == shifts.end() ? Eigen::Vector3d::Zero() : shift->second);
      for (int k = 0; k < 3; ++k)
        encode_component(place + k * component_bytes(l.component_type), l.component_type, l.normalized, local[k]);
      changed = true;
    }
    if (changed) update_bounds(s.accessor, buffers, json_edits);
  }
}

// Per mesh whose integer positions would leave their range: the shift (mesh space, a whole number
// of steps) that brings every position accessor of the mesh back inside. Throws when the range is
// too narrow for the marked extent.
std::map<std::size_t, Eigen::Vector3d> GltfDocument::mesh_shifts(
    const std::vector<std::vector<Eigen::Vector3d>>& targets) const {
  const double inf = std::numeric_limits<double>::infinity();
  std::map<std::size_t, std::pair<Eigen::Vector3d, Eigen::Vector3d>> allowed;  // mesh → shift interval
  std::map<std::size_t, double> step;
  for (std::size_t n = 0; n < position_sources_.size(); ++n) {
    const PositionSource& s = position_sources_[n];
    const Layout l = layout_of(s.accessor);
    const StoredRange range = stored_range(l.component_type, l.normalized);
    auto& [lo, hi] =
        allowed.try_emplace(s.mesh, Eigen::Vector3d::Constant(-inf), Eigen::Vector3d::Constant(inf)).first->second;
    if (range.step == 0) continue;
    step[s.mesh] = std::max(step[s.mesh], range.step);
    for (const Eigen::Vector3d& t : targets[n]) {
      lo = lo.cwiseMax(Eigen::Vector3d::Constant(range.lo) - t);
      hi = hi.cwiseMin(Eigen::Vector3d::Constant(range.hi) - t);
    }
  }
  std::map<std::size_t, Eigen::Vector3d> shifts;
  for (const auto& [mesh, interval] : allowed) {
    const auto& [lo, hi] = interval;
    if ((lo.array() <= 0).all() && (hi.array() >= 0).all()) continue;
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      if (lo[k] > 0) d[k] = std::ceil(lo[k] / step[mesh] - 1e-9) * step[mesh];
      else if (hi[k] < 0) d[k] = std::floor(hi[k] / step[mesh] + 1e-9) * step[mesh];
      if (d[k] < lo[k] - 1e-12 || d[k] > hi[k] + 1e-12)
        throw MeshIoError(source_ + ": the marked positions of mesh " + std::to_string(mesh) +
                          " span more than its quantized POSITION type can hold");
    }
    shifts[mesh] = d;
  }
  return shifts;
}

// Nodes that place a shifted mesh take the shift back (M·T(−d)); their children are kept where
// they were (T(d)·M). Refused where a node's transform is animated or drives a skin: a fixed
// correction would not hold there.
void GltfDocument::shift_nodes(const std::map<std::size_t, Eigen::Vector3d>& shifts, ByteEdits& json_edits) const {
  if (shifts.empty()) return;
  std::set<std::size_t> animated;
  for (const Json& a : json_.value("animations", Json::array()))
    for (const Json& c : a.value("channels", Json::array()))
      if (c.is_object() && c.contains("target") && c["target"].value("path", std::string()) != "weights" &&
          c["target"].contains("node") && c["target"]["node"].is_number_unsigned())
        animated.insert(c["target"]["node"].get<std::size_t>());
  std::map<std::size_t, std::pair<Eigen::Vector3d, Eigen::Vector3d>> correction;  // node → (before, after)
  const auto node_of = [&](std::size_t index) -> const Json& { return item("nodes", index); };
  for (const auto& shift : shifts) {
    const std::size_t mesh = shift.first;
    const Eigen::Vector3d& d = shift.second;
    for (const std::size_t n : mesh_nodes_.at(mesh)) {
      const Json& node = node_of(n);
      const auto refuse = [&](const std::string& why) {
        throw MeshIoError(source_ + ": the marked positions of mesh " + std::to_string(mesh) +
                          " leave the range of its quantized POSITION type, and node " + std::to_string(n) +
                          " cannot take the shift back: " + why);
      };
      if (node.contains("skin")) refuse("it is skinned");
      if (animated.count(n)) refuse("its transform is animated");
      auto& own = correction.try_emplace(n, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()).first->second;
      own.second -= d;
      for (const Json& c : node.value("children", Json::array())) {
        const std::size_t child = as_index(c, "a child node");
        if (animated.count(child)) refuse("its child node " + std::to_string(child) + " is animated");
        correction.try_emplace(child, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()).first->second.first += d;
      }
    }
  }
  for (const auto& [n, c] : correction) {
    const Json& node = node_of(n);
    const Matrix4 m = node_matrix(node);
    const std::string base = "/nodes/" + std::to_string(n);
    const auto numbers = [](const double* v, int count) {
      std::string text = "[";
      for (int i = 0; i < count; ++i) text += (i ? "," : "") + number_text(v[i]);
      return text + "]";
    };
    if (node.contains("matrix")) {
      Matrix4 shifted = m;
      shifted.col(3).head<3>() += c.first + m.topLeftCorner<3, 3>() * c.second;
      json_edits.replace(spans_->value(base + "/matrix"), numbers(shifted.data(), 16));  // column-major, as glTF
      continue;
    }
    Eigen::Vector3d t = m.col(3).head<3>() + c.first + m.topLeftCorner<3, 3>() * c.second;
    if (spans_->has(base + "/translation")) {
      json_edits.replace(spans_->value(base + "/translation"), numbers(t.data(), 3));
    } else {
      const std::size_t at = spans_->object_start(base);
      json_edits.replace({at, at}, "\"translation\":" + numbers(t.data(), 3) + ",");
    }
  }
}

// NORMAL and TANGENT turned by their vertex's rotation (in world space: normals by the inverse
// transpose of the node's matrix, tangents by the matrix), written back in their own type, as
// long as they were (unit vectors stay unit after quantization), with any bounds they declare.
void GltfDocument::write_directions(const NormalRotations& rotations, std::vector<Buffer>& buffers,
                                    ByteEdits& json_edits) const {
  std::set<std::pair<int, std::size_t>> done;
  std::set<int> turned_accessors;
  for (const Primitive& p : primitives_) {
    if (p.position_source < 0) continue;
    const PositionSource& s = position_sources_[static_cast<std::size_t>(p.position_source)];
    const Eigen::Matrix3d linear = p.world.topLeftCorner<3, 3>();
    const Eigen::Matrix3d normal_matrix = linear.inverse().transpose();
    for (const auto& [accessor, is_normal] : {std::pair{p.normal, true}, std::pair{p.tangent, false}}) {
      if (accessor < 0) continue;
      const Layout l = layout_of(static_cast<std::size_t>(accessor));
      for (std::size_t i = 0; i < l.count; ++i) {
        const Eigen::Quaterniond& r = rotations[s.first_slot + i];
        if (r.w() == 1.0 || !done.insert({accessor, i}).second) continue;
        unsigned char* place = element_place(l, i, buffers);
        if (!place) continue;
        const Eigen::Vector4d e = element(l, i, buffers);
        const Eigen::Vector3d local = e.head<3>();
        const double length = local.norm();
        if (!(length > 0)) continue;
        const Eigen::Vector3d world =
            is_normal ? Eigen::Vector3d(normal_matrix * local) : Eigen::Vector3d(linear * local);
        const Eigen::Vector3d turned = r * world;
        Eigen::Vector3d back =
            is_normal ? Eigen::Vector3d(linear.transpose() * turned) : Eigen::Vector3d(linear.inverse() * turned);
        encode_direction(place, l.component_type, l.normalized, back.normalized(), length);
        turned_accessors.insert(accessor);
      }
    }
  }
  for (const int accessor : turned_accessors) {
    const std::string base = "/accessors/" + std::to_string(accessor);
    if (spans_->has(base + "/min") || spans_->has(base + "/max"))
      update_bounds(static_cast<std::size_t>(accessor), buffers, json_edits);
  }
}

std::size_t align4(std::size_t n) { return (n + 3) / 4 * 4; }

// A Draco primitive whose points moved: its stream encoded again. Its view keeps its offset and
// takes the new length (padded to 4 bytes); the views after it in its buffer move by the
// change, their offsets patched, and so does the buffer's length.
void GltfDocument::write_draco(const Vertices& P, std::vector<Buffer>& buffers, ByteEdits& json_edits) const {
  std::map<int, std::vector<std::pair<std::size_t, std::string>>> replaced;  // buffer → (view, new bytes)
  for (const DracoSource& d : draco_) {
    Vertices local = d.codec.positions();
    const Matrix4 inverse = d.world.inverse();
    bool changed = false;
    for (Eigen::Index i = 0; i < local.rows(); ++i) {
      const auto slot = static_cast<Eigen::Index>(d.first_slot) + i;
      if (P.row(slot) == positions_.row(slot)) continue;
      local.row(i) = (inverse * P.row(slot).transpose().homogeneous()).head<3>().transpose();
      changed = true;
    }
    if (!changed) continue;
    std::string encoded = d.codec.encode(local);
    const Vertices decoded = DracoPrimitive(encoded, d.position_id).positions();  // the bounds of what readers will see
    Eigen::Vector4d lo = Eigen::Vector4d::Zero(), hi = lo;
    lo.head<3>() = decoded.colwise().minCoeff().transpose();
    hi.head<3>() = decoded.colwise().maxCoeff().transpose();
    set_bounds(d.accessor, lo, hi, 3, kFloat, json_edits);
    replaced[view_of(d.view).buffer].emplace_back(d.view, std::move(encoded));
  }
  for (auto& [buffer, views] : replaced) {
    std::sort(views.begin(), views.end(),
              [&](const auto& a, const auto& b) { return view_of(a.first).offset < view_of(b.first).offset; });
    const std::string& old = buffers[static_cast<std::size_t>(buffer)].bytes;
    std::string rebuilt;
    std::size_t at = 0;
    std::vector<std::pair<std::size_t, long long>> shifts;  // (old end of a replaced view, shift after it)
    for (const auto& [view, bytes] : views) {
      const View v = view_of(view);
      rebuilt.append(old, at, v.offset - at);
      rebuilt.append(bytes);
      rebuilt.append(align4(bytes.size()) - bytes.size(), '\0');
      at = std::min(old.size(), v.offset + align4(v.length));
      shifts.emplace_back(v.offset + v.length, static_cast<long long>(rebuilt.size()) - static_cast<long long>(at));
      set_member("/bufferViews/" + std::to_string(view), "byteLength", bytes.size(), json_edits);
    }
    rebuilt.append(old, at, std::string::npos);
    const Json& all = json_.value("bufferViews", Json::array());
    long long last_view_end = 0;  // after the rewrite
    for (std::size_t view = 0; view < all.size(); ++view) {
      const View v = view_of(view);
      if (v.buffer != buffer) continue;
      long long by = 0;
      for (const auto& [end, shift] : shifts)
        if (v.offset >= end) by = shift;
      const auto own = std::find_if(views.begin(), views.end(), [&](const auto& r) { return r.first == view; });
      const long long length =
          own != views.end() ? static_cast<long long>(own->second.size()) : static_cast<long long>(v.length);
      last_view_end = std::max(last_view_end, static_cast<long long>(v.offset) + by + length);
      if (by != 0)
        set_member("/bufferViews/" + std::to_string(view), "byteOffset",
                   static_cast<std::uint64_t>(static_cast<long long>(v.offset) + by), json_edits);
    }
    // The declared length keeps its distance to the end of the bytes (GLB padding), but always
    // covers every view and never exceeds the bytes.
    const long long declared =
        static_cast<long long>(whole(json_["buffers"][static_cast<std::size_t>(buffer)], "byteLength", 0));
    const long long resized =
        std::clamp(declared + static_cast<long long>(rebuilt.size()) - static_cast<long long>(old.size()),
                   std::min<long long>(std::max<long long>(last_view_end, 1), static_cast<long long>(rebuilt.size())),
                   static_cast<long long>(rebuilt.size()));
    set_member("/buffers/" + std::to_string(buffer), "byteLength", static_cast<std::uint64_t>(resized), json_edits);
    buffers[static_cast<std::size_t>(buffer)].bytes = std::move(rebuilt);
  }
}

DocumentFiles GltfDocument::write(const Vertices& P, const NormalRotations& rotations,
                                  const CompanionNames& names) const {
  if (P.rows() != positions_.rows())
    throw MeshIoError(source_ + ": " + std::to_string(P.rows()) + " positions for " +
                      std::to_string(positions_.rows()) + " slots");
  if (P == positions_ && (rotations.empty() || std::all_of(rotations.begin(), rotations.end(),
                                                           [](const auto& q) { return q.w() == 1.0; }))) {
    DocumentFiles same{{"", bytes_}};
    return same;
  }
  try {
    if (const std::string problem = aliasing_problem(); !problem.empty()) throw MeshIoError(source_ + ": " + problem);
    std::vector<Buffer> buffers = buffers_;
    ByteEdits json_edits;
    write_positions(P, buffers, json_edits);
    if (!rotations.empty()) write_directions(rotations, buffers, json_edits);
    write_draco(P, buffers, json_edits);
    return assemble(buffers, json_edits, names);
  } catch (const nlohmann::json::exception& e) {  // a member the reader did not need, of the wrong type
    throw MeshIoError(source_ + ": malformed glTF: " + e.what());
  }
}

// The files: the JSON with its edits (and any data URI re-encoded); for a GLB the container
// rebuilt around the new JSON and binary chunks (other chunks kept); external buffers that
// changed, by their URI.
DocumentFiles GltfDocument::assemble(const std::vector<Buffer>& buffers, const ByteEdits& edits,
                                     const CompanionNames& names) const {
  ByteEdits all = edits;
  DocumentFiles files;
  std::string bin;
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    if (buffers[i].bytes == buffers_[i].bytes) continue;
    switch (buffers[i].origin) {
      case Buffer::Origin::glb_chunk:
        bin = buffers[i].bytes;
        break;
      case Buffer::Origin::file: {
        const std::string uri = names ? names(buffers[i].uri) : buffers[i].uri;
        if (uri != buffers[i].uri)
          all.replace(spans_->value("/buffers/" + std::to_string(i) + "/uri"), Json(uri).dump());
        files[uri] = buffers[i].bytes;
        break;
      }
      case Buffer::Origin::data_uri: {
        const std::string& uri = buffers_[i].uri;
        const std::string prefix = uri.substr(0, uri.find(',') + 1);
        all.replace(spans_->value("/buffers/" + std::to_string(i) + "/uri"),
                    Json(prefix + base64_encode(buffers[i].bytes)).dump());
        break;
      }
    }
  }
  const std::string json = all.empty() ? json_text_ : all.apply(json_text_);
  if (!binary_) {
    files[""] = json;
    return files;
  }
  // GLB: header, JSON chunk (padded with spaces), then the other chunks in order (padded with zeros).
  const auto put32 = [](std::string& out, std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  std::string out(12, '\0');
  std::string padded_json = json;
  padded_json.append(align4(padded_json.size()) - padded_json.size(), ' ');
  put32(out, static_cast<std::uint32_t>(padded_json.size()));
  put32(out, kJsonChunk);
  out += padded_json;
  for (std::size_t c = 1; c < chunks_.size(); ++c) {
    std::string data =
        chunks_[c].type == kBinChunk && !bin.empty() ? bin : bytes_.substr(chunks_[c].offset, chunks_[c].length);
    data.append(align4(data.size()) - data.size(), '\0');
    put32(out, static_cast<std::uint32_t>(data.size()));
    put32(out, chunks_[c].type);
    out += data;
  }
  const std::uint32_t magic = kGlbMagic, version = 2, length = static_cast<std::uint32_t>(out.size());
  std::memcpy(out.data(), &magic, 4);
  std::memcpy(out.data() + 4, &version, 4);
  std::memcpy(out.data() + 8, &length, 4);
  files[""] = std::move(out);
  return files;
}

}  // namespace

}  // namespace meshmark

namespace meshmark {

std::unique_ptr<MeshDocument> read_gltf_document(std::string bytes, bool binary, const DocumentReadOptions& options,
                                                 const std::string& source) {
  try {
    return std::make_unique<GltfDocument>(std::move(bytes), binary, options, source);
  } catch (const nlohmann::json::exception& e) {  // a member of the wrong JSON type
    throw MeshIoError(source + ": malformed glTF: " + e.what());
  }
}

}  // namespace meshmark
