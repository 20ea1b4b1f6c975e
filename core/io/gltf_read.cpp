// Reading a glTF document: the GLB container, buffers (chunk, data URI or companion file),
// accessors with their views and sparse parts, and the default scene's triangle primitives in
// world space (Draco ones decoded), each instance of a mesh after the first as the scene's.

#include <Eigen/Geometry>
#include <algorithm>
#include <cstring>

#include "core/io/base64.hpp"
#include "core/io/gltf_components.hpp"
#include "core/io/gltf_document.hpp"
#include "core/util/json_nesting_depth.hpp"

namespace meshmark {

namespace gltf {

GltfDocument::GltfDocument(std::string bytes, bool binary, const DocumentReadOptions& options,
                           const std::string& source)
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
  if (version.rfind('2', 0) != 0) fail("only glTF 2.0 is read (asset.version is '" + version.substr(0, 10) + "')");
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

void GltfDocument::split_container() {
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

void GltfDocument::load_buffers(const DocumentReadOptions& options) {
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
          fail("buffers " + std::to_string(it->second) + " and " + std::to_string(i) + " both name the file '" + b.uri +
               "'; each buffer must be a file of its own");
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

const Json& GltfDocument::item(const char* array, std::size_t index) const {
  const auto it = json_.find(array);
  if (it == json_.end() || !it->is_array() || index >= it->size() || !(*it)[index].is_object())
    fail(std::string("no ") + array + " entry " + std::to_string(index));
  return (*it)[index];
}

std::size_t GltfDocument::index_of(const Json& j, const char* key) const {
  return as_index(j.at(key), std::string("'") + key + "'");
}

std::size_t GltfDocument::whole(const Json& j, const char* key, std::size_t fallback) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_number_unsigned() || it->get<std::uint64_t>() > (std::uint64_t{1} << 48))
    fail(std::string("'") + key + "' must be a non-negative integer");
  return it->get<std::size_t>();
}

std::size_t GltfDocument::as_index(const Json& v, const std::string& what) const {
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > 0x7fffffffu) fail(what + " must be an index");
  return v.get<std::size_t>();
}

GltfDocument::View GltfDocument::view_of(std::size_t index) const {
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

Layout GltfDocument::layout_of(std::size_t accessor) const {
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

void GltfDocument::read_sparse(std::size_t accessor, const Json& s, std::size_t element, Layout& l) const {
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

Eigen::Vector4d GltfDocument::element(const Layout& l, std::size_t i, const std::vector<Buffer>& buffers) const {
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

unsigned char* GltfDocument::element_place(const Layout& l, std::size_t i, std::vector<Buffer>& buffers) const {
  if (const auto s = l.sparse.find(static_cast<std::uint32_t>(i)); s != l.sparse.end())
    return reinterpret_cast<unsigned char*>(buffers[static_cast<std::size_t>(l.sparse_buffer)].bytes.data()) +
           s->second;
  if (l.buffer < 0) return nullptr;
  return reinterpret_cast<unsigned char*>(buffers[static_cast<std::size_t>(l.buffer)].bytes.data()) + l.offset +
         i * l.stride;
}

Matrix4 GltfDocument::node_matrix(const Json& node) {
  Matrix4 m = Matrix4::Identity();
  if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        m(r, c) = node["matrix"][4 * static_cast<std::size_t>(c) + static_cast<std::size_t>(r)]
                      .get<double>();  // column-major
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

void GltfDocument::walk_scene() {
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

void GltfDocument::visit(std::size_t index, const Matrix4& parent, std::vector<char>& visiting, int depth) {
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

void GltfDocument::add_mesh_instance(std::size_t mesh, const Matrix4& world) {
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
  for (std::size_t p = 0; p < primitives.size(); ++p) add_primitive(mesh, p, primitives[p], world, instance.face_slots);
}

void GltfDocument::add_further_instance(Instance& first, const Matrix4& world) {
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

void GltfDocument::index_slots(Instance& first) {
  std::map<int, int> vertex_of_slot;
  std::vector<int> faces;
  for (const int slot : first.face_slots) {
    const auto [at, added] = vertex_of_slot.emplace(slot, static_cast<int>(first.slots.size()));
    if (added) first.slots.push_back(slot);
    faces.push_back(at->second);
  }
  first.faces = Eigen::Map<const Faces>(faces.data(), static_cast<Eigen::Index>(faces.size() / 3), 3);
}

void GltfDocument::add_primitive(std::size_t mesh, std::size_t p, const Json& primitive, const Matrix4& world,
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

void GltfDocument::add_slot(const Eigen::Vector3d& local, const Matrix4& world, const std::string& where) {
  const Eigen::Vector3d w = (world * local.homogeneous()).head<3>();
  builder_.add_vertex(w.x(), w.y(), w.z(), where);
  slot_local_.push_back(local);
}

void GltfDocument::add_triangles(const std::vector<std::uint32_t>& indices, int mode, std::size_t count,
                                 std::size_t first_slot, const std::string& name, std::vector<int>& face_slots,
                                 DocumentPart& part) {
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

}  // namespace gltf

std::unique_ptr<MeshDocument> read_gltf_document(std::string bytes, bool binary, const DocumentReadOptions& options,
                                                 const std::string& source) {
  try {
    return std::make_unique<gltf::GltfDocument>(std::move(bytes), binary, options, source);
  } catch (const nlohmann::json::exception& e) {  // a member of the wrong JSON type
    throw MeshIoError(source + ": malformed glTF: " + e.what());
  }
}

}  // namespace meshmark
