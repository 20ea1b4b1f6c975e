// 3MF as a document: a ZIP package whose root model part (found through _rels/.rels) holds
// objects with <vertices> and <triangles>, objects made of <components>, and a <build> of items,
// each with an optional affine transform (3MF's row-vector "m00 m01 m02 m10 ... m32"). The slots
// are the vertices of every mesh object the build places, in world space by the object's first
// placement; further placements are the scene's other instances. Written back as the same
// package: only the x, y, z values of moved vertices change in the model parts, which are
// compressed again; every other part (textures, relationships, thumbnails, metadata) keeps its
// bytes. Components may live in other model parts (the production extension's p:path, as
// slicers write them); those parts are read and written alike.

#include <charconv>
#include <map>
#include <optional>
#include <set>
#include <limits>
#include <string>
#include <vector>

#include "core/io/byte_edits.hpp"
#include "core/io/number_text.hpp"
#include "core/io/document_readers.hpp"
#include "core/io/mesh_builder.hpp"
#include "core/io/scene_budget.hpp"
#include "core/io/xml_tags.hpp"
#include "core/io/zip_archive.hpp"

namespace meshmark {

namespace {

constexpr std::string_view kCoreNamespace = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
constexpr std::string_view kModelRelationship = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";

using Affine = Eigen::Matrix4d;  // column-vector convention inside; 3MF's row form converted on read

struct MeshObject {
  std::string label;  // "object 1 'name'"
  std::string type = "model";
  std::vector<Eigen::Vector3d> vertices;  // object space
  std::vector<std::array<ByteSpan, 3>> spans;
  std::vector<std::array<long long, 3>> triangles;
  bool has_properties = false;  // pid / p1 on the object or its triangles
  bool is_mesh = false;
  struct Component {
    std::size_t part;  // the model part the object is in
    std::size_t object;
    Affine transform;
  };
  std::vector<Component> components;
};

// A model part: its name in the package and its text.
struct ModelPart {
  std::string name;
  std::string text;
};

using ObjectKey = std::pair<std::size_t, std::size_t>;  // model part, object id

class ThreeMfDocument : public MeshDocument {
 public:
  ThreeMfDocument(std::string bytes, const DocumentReadOptions& options, const std::string& source)
      : MeshDocument(MeshFormat::threemf),
        source_(source),
        archive_(std::move(bytes), options.limits.max_file_bytes, source),
        builder_(options.limits, source),
        scene_budget_(options.limits, source) {
    max_vertices_ = options.limits.max_vertices;
    max_faces_ = options.limits.max_faces;
    part_index(root_model_name());
    place_build();
    if (builder_.face_count() == 0) fail("the build places no triangle");
    const ReadResult r = builder_.finish();
    positions_ = r.mesh.V;
    triangles_ = r.mesh.F;
  }

  std::vector<DocumentPart> parts() const override { return parts_; }

  bool turns_directions() const override { return false; }

  DocumentFiles write(const Vertices& P, const NormalRotations&, const CompanionNames&) const override {
    if (P.rows() != positions_.rows())
      fail(std::to_string(P.rows()) + " positions for " + std::to_string(positions_.rows()) + " slots");
    std::vector<ByteEdits> edits(models_.size());
    for (const Placement& placed : slots_) {
      const MeshObject& object = objects_.at(placed.object);
      const Affine inverse = placed.world.inverse();
      for (std::size_t v = 0; v < object.vertices.size(); ++v) {
        const auto slot = static_cast<Eigen::Index>(placed.first_slot + v);
        if (P.row(slot) == positions_.row(slot)) continue;
        const Eigen::Vector3d local = (inverse * P.row(slot).transpose().homogeneous()).head<3>();
        for (int k = 0; k < 3; ++k)
          edits[placed.object.first].replace(object.spans[v][k], number_text(static_cast<float>(local[k])));
      }
    }
    std::map<std::string, std::string> contents;
    for (std::size_t m = 0; m < models_.size(); ++m)
      if (!edits[m].empty()) contents[models_[m].name] = edits[m].apply(models_[m].text);
    if (contents.empty()) return main_file_only(archive_.bytes());
    return main_file_only(archive_.with_contents(contents));
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw MeshIoError(source_ + ": " + what); }

  // --- the package ---------------------------------------------------------------------------

  // The target of the root relationship of the 3D model type; 3D/3dmodel.model by convention.
  std::string root_model_name() const {
    const ZipEntry* rels = archive_.find("_rels/.rels");
    if (!rels) return "3D/3dmodel.model";
    const std::string text = archive_.extract(*rels);
    XmlTagReader reader(text);
    XmlTag tag;
    while (reader.next(tag, source_ + ": _rels/.rels")) {
      if (tag.closing || tag.local_name() != "Relationship") continue;
      const XmlAttribute* type = tag.find("Type");
      const XmlAttribute* target = tag.find("Target");
      if (type && target && type->value == kModelRelationship) {
        std::string name(target->value);
        if (!name.empty() && name.front() == '/') name.erase(0, 1);
        return name;
      }
    }
    fail("_rels/.rels names no 3D model part");
  }

  // --- the model part ------------------------------------------------------------------------

  static std::optional<double> number(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double value = 0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    if (result.ec != std::errc() || result.ptr != text.data() + text.size() || !std::isfinite(value))
      return std::nullopt;
    return value;
  }

  std::size_t index_attribute(const XmlTag& tag, std::string_view name, const std::string& where) const {
    const XmlAttribute* a = tag.find(name);
    if (!a) fail(where + ": <" + std::string(tag.local_name()) + "> has no " + std::string(name));
    std::size_t value = 0;
    const auto result = std::from_chars(a->value.data(), a->value.data() + a->value.size(), value);
    if (result.ec != std::errc() || result.ptr != a->value.data() + a->value.size())
      fail(where + ": " + std::string(name) + "=\"" + std::string(a->value.substr(0, 20)) + "\" is not an index");
    return value;
  }

  // 3MF writes a transform as 12 numbers, the rows of a 4×3 matrix that multiplies row vectors.
  Affine transform_attribute(const XmlTag& tag, const std::string& where) const {
    Affine m = Affine::Identity();
    const XmlAttribute* a = tag.find("transform");
    if (!a) return m;
    std::string_view text = a->value;
    double values[12];
    for (double& v : values) {
      while (!text.empty() &&
             (text.front() == ' ' || text.front() == '\t' || text.front() == '\n' || text.front() == '\r'))
        text.remove_prefix(1);
      std::size_t end = 0;
      while (end < text.size() && text[end] != ' ' && text[end] != '\t' && text[end] != '\n' && text[end] != '\r')
        ++end;
      const auto parsed = number(text.substr(0, end));
      if (!parsed) fail(where + ": the transform is not 12 numbers");
      v = *parsed;
      text.remove_prefix(end);
    }
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 3; ++col) m(col, row) = values[row * 3 + col];
    if (!(std::abs(m.topLeftCorner<3, 3>().determinant()) > 0)) fail(where + ": the transform is singular");
    return m;
  }

  // The core namespace's prefix, from the <model> element's declarations ("" when it is the
  // default namespace).
  std::string core_prefix(const XmlTag& model) const {
    for (const XmlAttribute& a : model.attributes) {
      if (a.value != kCoreNamespace) continue;
      if (a.name == "xmlns") return "";
      if (a.name.substr(0, 6) == "xmlns:") return std::string(a.name.substr(6));
    }
    fail("the model is not in the 3MF core namespace");
  }

  // The index of a model part by its name (a leading '/' or not), read and parsed on first use.
  std::size_t part_index(std::string name) {
    if (!name.empty() && name.front() == '/') name.erase(0, 1);
    const ZipEntry* entry = archive_.find(name);
    if (!entry) fail("the package has no model part '" + name + "'");
    for (std::size_t m = 0; m < models_.size(); ++m)
      if (models_[m].name == entry->name) return m;
    models_.push_back({entry->name, archive_.extract(*entry)});
    parse_model(models_.size() - 1);
    return models_.size() - 1;
  }

  void parse_model(std::size_t part) {
    const std::string& text = models_[part].text;
    XmlTagReader reader(text);
    XmlTag tag;
    const std::string where = source_ + ": " + models_[part].name;
    std::string core;
    bool in_model = false, in_resources = false, in_build = false;
    MeshObject* object = nullptr;
    while (reader.next(tag, where)) {
      builder_.tick();
      if (!in_model) {
        if (tag.local_name() != "model" || tag.closing) fail("the model part does not start with <model>");
        core = core_prefix(tag);
        in_model = true;
        continue;
      }
      if (tag.prefix() != core) continue;  // an extension's element: kept as bytes, not read
      const std::string_view name = tag.local_name();
      const std::string at = where + ": line " + std::to_string(tag.line);
      if (name == "resources") in_resources = !tag.closing && !tag.empty;
      else if (name == "build") in_build = !tag.closing && !tag.empty;
      else if (name == "object" && in_resources) {
        if (tag.closing) {
          object = nullptr;
          continue;
        }
        const std::size_t object_id = index_attribute(tag, "id", at);
        if (objects_.count({part, object_id})) fail(at + ": two objects with id " + std::to_string(object_id));
        object = &objects_[{part, object_id}];
        object->label = "object " + std::to_string(object_id);
        if (const XmlAttribute* n = tag.find("name")) object->label += " '" + std::string(n->value.substr(0, 60)) + "'";
        if (const XmlAttribute* t = tag.find("type")) object->type = std::string(t->value);
        object->has_properties = tag.find("pid") != nullptr;
        if (tag.empty) object = nullptr;
      } else if (object && name == "mesh") {
        object->is_mesh = true;
      } else if (object && name == "vertex" && !tag.closing) {
        read_vertex(tag, *object, at);
      } else if (object && name == "triangle" && !tag.closing) {
        read_triangle(tag, *object, at);
      } else if (object && name == "component" && !tag.closing) {
        object->components.push_back(
            {part_path(tag, part), index_attribute(tag, "objectid", at), transform_attribute(tag, at)});
      } else if (in_build && name == "item" && !tag.closing && part == 0) {
        items_.push_back({part_path(tag, part), index_attribute(tag, "objectid", at), transform_attribute(tag, at)});
      }
    }
    if (!in_model) fail("the model part is empty");
  }

  // The model part an item or component refers to: another one when it has a production
  // extension path (p:path), else its own. Parts are read before the object is placed; the
  // reference is resolved now, while `tag` is valid.
  std::size_t part_path(const XmlTag& tag, std::size_t own) {
    for (const XmlAttribute& a : tag.attributes)
      if (a.name.size() > 5 && a.name.substr(a.name.size() - 5) == ":path") {
        pending_parts_.emplace_back(std::string(a.value));
        return kPending + pending_parts_.size() - 1;
      }
    return own;
  }

  void read_vertex(const XmlTag& tag, MeshObject& object, const std::string& at) {
    Eigen::Vector3d p;
    std::array<ByteSpan, 3> spans;
    const char* names[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      const XmlAttribute* a = tag.find(names[k]);
      if (!a) fail(at + ": a <vertex> without " + names[k]);
      const auto value = number(a->value);
      if (!value)
        fail(at + ": " + names[k] + "=\"" + std::string(a->value.substr(0, 30)) + "\" is not a finite number");
      p[k] = *value;
      spans[static_cast<std::size_t>(k)] = a->span;
    }
    if (++stored_vertices_ > max_vertices_)
      builder_.fail_limit(at, "more than " + std::to_string(max_vertices_) + " vertices");
    object.vertices.push_back(p);
    object.spans.push_back(spans);
  }

  void read_triangle(const XmlTag& tag, MeshObject& object, const std::string& at) {
    std::array<long long, 3> t;
    const char* names[3] = {"v1", "v2", "v3"};
    for (int k = 0; k < 3; ++k) {
      const std::size_t index = index_attribute(tag, names[k], at);
      // Past what a signed index holds it would wrap negative and pass the later range check.
      if (index > static_cast<std::size_t>(std::numeric_limits<long long>::max()))
        fail(at + ": " + names[k] + "=" + std::to_string(index) + " refers to vertex " + std::to_string(index) +
             ", which no object has");
      t[static_cast<std::size_t>(k)] = static_cast<long long>(index);
    }
    if (tag.find("pid") || tag.find("p1")) object.has_properties = true;
    if (++stored_triangles_ > max_faces_)
      builder_.fail_limit(at, "more than " + std::to_string(max_faces_) + " triangles");
    object.triangles.push_back(t);
  }

  // --- the build -----------------------------------------------------------------------------

  struct Placement {
    ObjectKey object;
    Affine world;
    std::size_t first_slot;
  };

  void place_build() {
    if (items_.empty()) fail("the build has no item");
    for (const MeshObject::Component& item : items_) place(resolve(item.part), item.object, item.transform, 0);
  }

  std::size_t resolve(std::size_t part) {
    if (part < kPending) return part;
    return part_index(pending_parts_[part - kPending]);
  }

  void place(std::size_t part, std::size_t id, const Affine& world, int depth) {
    if (depth > 32) fail("components nest deeper than 32 levels (a cycle?)");
    scene_budget_.visit();
    const ObjectKey key{part, id};
    if (!objects_.count(key))
      fail("object " + std::to_string(id) + " is placed but not defined in " + models_[part].name);
    const std::vector<MeshObject::Component> components = objects_.at(key).components;  // parts may be read meanwhile
    for (const MeshObject::Component& c : components) place(resolve(c.part), c.object, world * c.transform, depth + 1);
    const MeshObject& object = objects_.at(key);
    if (!object.is_mesh) return;
    if (auto seen = part_of_.find(key); seen != part_of_.end()) {
      ++parts_[seen->second].instances;
      add_further_instance(first_placement(key), object, world);
      return;
    }
    const std::size_t first = builder_.vertex_count();
    for (const Eigen::Vector3d& local : object.vertices) {
      const Eigen::Vector3d w = (world * local.homogeneous()).head<3>();
      builder_.add_vertex(w.x(), w.y(), w.z(), object.label);
    }
    for (const auto& t : object.triangles) {
      long long corners[3];
      for (int k = 0; k < 3; ++k) {
        if (t[static_cast<std::size_t>(k)] >= static_cast<long long>(object.vertices.size()))
          fail(object.label + ": a triangle refers to vertex " + std::to_string(t[static_cast<std::size_t>(k)]) +
               " of " + std::to_string(object.vertices.size()));
        corners[k] = static_cast<long long>(first) + t[static_cast<std::size_t>(k)];
      }
      builder_.add_polygon(corners, 3, object.label);
    }
    slots_.push_back({key, world, first});
    DocumentPart p;
    p.name = object.label;
    p.stored_vertices = object.vertices.size();
    p.triangles = object.triangles.size();
    if (object.type != "model") p.attributes.push_back("type " + object.type);
    if (object.has_properties) p.attributes.push_back("triangle properties (colours or texture coordinates)");
    if (part != 0) p.name += " in " + models_[part].name;
    part_of_[key] = parts_.size();
    parts_.push_back(p);
  }

  // A further placement of a mesh object: in the scene, a copy of its first placement's slots.
  void add_further_instance(const Placement& first, const MeshObject& object, const Affine& world) {
    scene_budget_.add_instance(object.vertices.size(), object.triangles.size());
    const auto n = static_cast<Eigen::Index>(object.vertices.size());
    FurtherInstance instance;
    instance.mesh.V.resize(n, 3);
    for (Eigen::Index v = 0; v < n; ++v) {
      instance.mesh.V.row(v) =
          (world * object.vertices[static_cast<std::size_t>(v)].homogeneous()).head<3>().transpose();
      instance.slots.push_back(static_cast<int>(first.first_slot) + static_cast<int>(v));
    }
    instance.mesh.F.resize(static_cast<Eigen::Index>(object.triangles.size()), 3);
    for (std::size_t f = 0; f < object.triangles.size(); ++f)
      for (int k = 0; k < 3; ++k)
        instance.mesh.F(static_cast<Eigen::Index>(f), k) =
            static_cast<int>(object.triangles[f][static_cast<std::size_t>(k)]);
    instance.move_to_slot = move_to_slot(first.world.topLeftCorner<3, 3>(), world.topLeftCorner<3, 3>());
    further_instances_.push_back(std::move(instance));
  }

  const Placement& first_placement(const ObjectKey& key) const {
    for (const Placement& p : slots_)
      if (p.object == key) return p;
    fail("object " + std::to_string(key.second) + " has no first placement");
  }

  std::string source_;
  ZipArchive archive_;
  MeshBuilder builder_;
  SceneBudget scene_budget_;
  static constexpr std::size_t kPending = std::size_t{1} << 40;  // part numbers ≥ this: pending_parts_
  std::size_t max_vertices_ = 0, max_faces_ = 0, stored_vertices_ = 0, stored_triangles_ = 0;
  std::vector<ModelPart> models_;           // [0] the root model part
  std::vector<std::string> pending_parts_;  // model part paths named by p:path
  std::map<ObjectKey, MeshObject> objects_;
  std::vector<MeshObject::Component> items_;
  std::vector<Placement> slots_;
  std::map<ObjectKey, std::size_t> part_of_;  // mesh object → its DocumentPart
  std::vector<DocumentPart> parts_;
};

}  // namespace

std::unique_ptr<MeshDocument> read_3mf_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source) {
  return std::make_unique<ThreeMfDocument>(std::move(bytes), options, source);
}

}  // namespace meshmark
