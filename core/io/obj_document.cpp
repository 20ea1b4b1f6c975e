// Wavefront OBJ as a document: `v x y z [w | r g b]` and `f a b c ...` with `a`, `a/t`, `a//n` or
// `a/t/n` corners (negative indices count back). Every line but the coordinates of moved `v` lines
// (and the `vn` lines whose vertices turned) is written back byte for byte: `vt`, `vn`, groups,
// objects, materials, smoothing groups, comments, `l` lines, vertex colours, polygons as polygons.

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/io/byte_edits.hpp"
#include "core/io/number_text.hpp"
#include "core/io/document_readers.hpp"
#include "core/io/mesh_builder.hpp"
#include "core/io/text_cursor.hpp"
#include "core/mesh/normal_rotations.hpp"

namespace meshmark {

namespace {

class ObjDocument : public MeshDocument {
 public:
  ObjDocument(std::string bytes, const DocumentReadOptions& options, const std::string& source)
      : MeshDocument(MeshFormat::obj), bytes_(std::move(bytes)), for_writing_(options.for_writing) {
    parse(options, source);
    if (!for_writing_) std::string().swap(bytes_);  // read: nothing will be written back from them
  }

  std::vector<DocumentPart> parts() const override {
    std::vector<DocumentPart> parts;
    for (const auto& [name, triangles] : triangles_by_material_) {
      DocumentPart p;
      p.name = name.empty() ? "(no material)" : "usemtl " + name;
      p.stored_vertices = static_cast<std::size_t>(positions_.rows());
      p.triangles = triangles;
      if (texcoords_ > 0) p.attributes.push_back("vt ×" + std::to_string(texcoords_));
      if (!normal_tokens_.empty()) p.attributes.push_back("vn ×" + std::to_string(normal_tokens_.size()));
      if (coloured_) p.attributes.push_back("vertex colours");
      parts.push_back(std::move(p));
    }
    return parts;
  }

  bool turns_directions() const override { return !normal_tokens_.empty(); }

  DocumentFiles write(const Vertices& P, const NormalRotations& rotations, const CompanionNames&) const override {
    if (!for_writing_) throw std::logic_error("an OBJ document read only to be read cannot be written back");
    ByteEdits edits;
    edits.reserve(static_cast<std::size_t>(3 * P.rows()), static_cast<std::size_t>(3 * P.rows()) * 12);
    const CoordinateText text = CoordinateText::of_points(P);
    char buffer[CoordinateText::kMaxChars];
    for (Eigen::Index v = 0; v < P.rows(); ++v) {
      if (P.row(v) == positions_.row(v)) continue;
      for (int k = 0; k < 3; ++k)
        edits.replace(vertex_tokens_[static_cast<std::size_t>(v)][k], {buffer, text.write(P(v, k), buffer)});
    }
    if (!rotations.empty()) rotate_normals(rotations, edits);
    return main_file_only(edits.empty() ? bytes_ : edits.apply(bytes_));
  }

 private:
  void parse(const DocumentReadOptions& options, const std::string& source) {
    MeshBuilder builder(options.limits, source);
    TextCursor cursor(bytes_);
    std::vector<long long> corners;
    std::string material;
    while (!cursor.at_end()) {
      cursor.skip_blanks();
      const std::string_view keyword = cursor.token();
      if (keyword == "v") read_vertex(cursor, builder);
      else if (keyword == "vn") read_normal(cursor, builder);
      else if (keyword == "vt") ++texcoords_;
      else if (keyword == "f") read_face(cursor, builder, corners, material);
      else if (keyword == "usemtl") material = std::string(cursor.rest_of_line());
      else if (keyword == "mtllib") add_libraries(cursor.rest_of_line(), options, source);
      else if (!keyword.empty() && keyword.front() != '#')
        for (char c : keyword)  // a keyword we do not use (g, o, s, mtllib, l, ...): it must be text
          if (static_cast<unsigned char>(c) < 9 || c == 0x7f)
            builder.fail(line_label(cursor.line()), "binary data in an OBJ file (is it really OBJ?)");
      cursor.next_line();
    }
    if (builder.face_count() == 0) builder.fail("", "no faces found (is this an OBJ mesh file?)");
    take_scene(builder.finish());
  }

  // Material libraries, and the texture maps they name (the last word of a map statement, after
  // its options), as companions. A library that cannot be read is still listed.
  void add_libraries(std::string_view names, const DocumentReadOptions& options, const std::string& source) {
    TextCursor words(names);
    for (std::string_view name = words.token(); !name.empty(); name = words.token()) {
      const std::string library(name);
      if (!add_companion(library, source) || !options.companion) continue;
      std::string text;
      try {
        text = options.companion(library);
      } catch (const MeshIoError&) {
        continue;
      }
      TextCursor mtl(text);
      while (!mtl.at_end()) {
        mtl.skip_blanks();
        const std::string_view keyword = mtl.token();
        if (keyword.rfind("map_", 0) == 0 || keyword == "bump" || keyword == "disp" || keyword == "decal" ||
            keyword == "refl" || keyword == "norm") {
          std::string_view last;
          for (std::string_view w = mtl.token(); !w.empty(); w = mtl.token()) last = w;
          if (!last.empty()) add_companion(std::string(last), source);
        }
        mtl.next_line();
      }
    }
  }

  ByteSpan span_of(std::string_view token) const {
    const auto begin = static_cast<std::size_t>(token.data() - bytes_.data());
    return {begin, begin + token.size()};
  }

  void read_vertex(TextCursor& cursor, MeshBuilder& builder) {
    double xyz[3];
    std::array<ByteSpan, 3> spans;
    for (int k = 0; k < 3; ++k) {
      cursor.skip_blanks();
      const std::size_t at = cursor.position();
      if (!cursor.read_number(xyz[k])) builder.fail(line_label(cursor.line()), "a 'v' line needs three numbers x y z");
      spans[static_cast<std::size_t>(k)] = {at, cursor.position()};
    }
    int extra = 0;
    for (double ignored; cursor.read_number(ignored);) ++extra;
    coloured_ = coloured_ || extra >= 3;
    builder.add_vertex(xyz[0], xyz[1], xyz[2], InputPlace::line(cursor.line()));
    if (for_writing_) vertex_tokens_.push_back(spans);
  }

  void read_normal(TextCursor& cursor, MeshBuilder& builder) {
    std::array<ByteSpan, 3> spans;
    Eigen::Vector3d n;
    for (int k = 0; k < 3; ++k) {
      cursor.skip_blanks();
      const std::size_t at = cursor.position();
      if (!cursor.read_number(n[k])) builder.fail(line_label(cursor.line()), "a 'vn' line needs three numbers");
      spans[static_cast<std::size_t>(k)] = {at, cursor.position()};
    }
    normal_tokens_.push_back(spans);
    normals_.push_back(n);
  }

  void read_face(TextCursor& cursor, MeshBuilder& builder, std::vector<long long>& corners,
                 const std::string& material) {
    corners.clear();
    const auto defined = static_cast<long long>(builder.vertex_count());
    while (!cursor.at_line_end('#')) {
      const std::string_view token = cursor.token();
      long long index = 0;
      if (!parse_leading_integer(token, index) || index == 0)
        builder.fail(line_label(cursor.line()), "face corner '" + std::string(token.substr(0, 40)) +
                                                    "' is not a vertex index (1-based, or negative)");
      const long long v = index > 0 ? index - 1 : defined + index;
      corners.push_back(v);
      // A normal reference (a/t/n or a//n) ties this vertex to that normal.
      const std::size_t second = token.find('/', token.find('/') + 1);
      long long n = 0;
      if (token.find('/') != std::string_view::npos && second != std::string_view::npos &&
          parse_leading_integer(token.substr(second + 1), n) && n != 0) {
        const long long normal = n > 0 ? n - 1 : static_cast<long long>(normals_.size()) + n;
        if (normal >= 0 && static_cast<std::size_t>(normal) < normals_.size() && v >= 0 && v < defined)
          normal_users_[static_cast<std::size_t>(normal)].insert(static_cast<int>(v));
      }
    }
    const std::size_t before = builder.face_count();
    builder.add_polygon(corners.data(), corners.size(), InputPlace::line(cursor.line()));
    triangles_by_material_[material] += builder.face_count() - before;
  }

  // Each `vn` turned by the rotations of the vertices that use it.
  void rotate_normals(const NormalRotations& rotations, ByteEdits& edits) const {
    for (const auto& [normal, users] : normal_users_) {
      std::vector<const Eigen::Quaterniond*> r;
      for (const int v : users) r.push_back(&rotations[static_cast<std::size_t>(v)]);
      const Eigen::Vector3d& n = normals_[normal];
      const Eigen::Vector3d turned = rotate_shared(n, r);
      if (turned == n) continue;
      for (int k = 0; k < 3; ++k) edits.replace(normal_tokens_[normal][k], unit_vector_text()(turned[k]));
    }
  }

  std::string bytes_;
  std::vector<std::array<ByteSpan, 3>> vertex_tokens_, normal_tokens_;
  std::vector<Eigen::Vector3d> normals_;
  std::map<std::size_t, std::set<int>> normal_users_;  // vn index → the v indices using it
  std::map<std::string, std::size_t> triangles_by_material_;
  std::size_t texcoords_ = 0;
  bool coloured_ = false;
  bool for_writing_ = true;  // false: the vertices' places are not kept, nor the bytes once parsed
};

}  // namespace

std::unique_ptr<MeshDocument> read_obj_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source) {
  return std::make_unique<ObjDocument>(std::move(bytes), options, source);
}

}  // namespace meshmark
