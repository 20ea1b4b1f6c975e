// STL as a document, binary (80-byte header, count, 50 bytes per triangle) and ASCII (`solid ...
// facet normal ... outer loop vertex x y z ...`). STL has no shared vertices: corners at the same
// exact position are one stored vertex, numbered in order of first appearance (by sorting, so no
// file can make the welding quadratic). Written back in its own encoding: binary stays binary
// with its header and attribute bytes; the corners and the recomputed normal of facets with a
// moved corner change, nothing else. Facets whose corners weld together are kept in the file and
// left out of the surface (counted).

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/io/byte_edits.hpp"
#include "core/io/number_text.hpp"
#include "core/io/document_readers.hpp"
#include "core/io/mesh_builder.hpp"
#include "core/io/text_cursor.hpp"
#include "core/io/write_mesh.hpp"
#include "core/mesh/weld_positions.hpp"

namespace meshmark {

namespace {

bool looks_binary(std::string_view bytes) {
  if (bytes.size() < 84) return false;
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);  // STL is little endian; so are our targets
  return 84 + 50ull * count == bytes.size();
}

// Where one facet's numbers are: the normal and the three corners, three numbers each.
struct FacetPlaces {
  ByteSpan normal[3];
  ByteSpan corner[3][3];
};

// A binary facet's places follow from its index: 50 bytes a record after the 84 of the header.
FacetPlaces binary_facet_places(std::size_t facet) {
  const std::size_t record = 84 + 50 * facet;
  FacetPlaces places;
  for (std::size_t a = 0; a < 3; ++a) places.normal[a] = {record + 4 * a, record + 4 * a + 4};
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t a = 0; a < 3; ++a) {
      const std::size_t at = record + 12 + 12 * c + 4 * a;
      places.corner[c][a] = {at, at + 4};
    }
  return places;
}

std::string float_bytes(double value) {
  const float f = static_cast<float>(value);
  std::string raw(4, '\0');
  std::memcpy(raw.data(), &f, 4);
  return raw;
}

class StlDocument : public MeshDocument {
 public:
  StlDocument(std::string bytes, const DocumentReadOptions& options, const std::string& source)
      : MeshDocument(MeshFormat::stl), bytes_(std::move(bytes)) {
    MeshBuilder builder(options.limits, source);
    binary_ = looks_binary(bytes_);
    if (binary_) read_binary(builder);
    else if (bytes_.substr(0, 5) == "solid") read_ascii(builder);
    else if (bytes_.size() >= 84)
      builder.fail("",
                   "not an STL file: binary STL must be 84 + 50 × (triangle count) bytes long, "
                   "and ASCII STL must start with 'solid'");
    else builder.fail("", "not an STL file: too short (" + std::to_string(bytes_.size()) + " bytes)");
    weld(builder);
  }

  std::vector<DocumentPart> parts() const override {
    DocumentPart p;
    p.name = std::string(binary_ ? "binary" : "ascii") + " facets";
    p.stored_vertices = static_cast<std::size_t>(positions_.rows());
    p.triangles = facet_count_;
    if (collapsed_ > 0) p.attributes.push_back(std::to_string(collapsed_) + " facets with corners at one place");
    return {p};
  }

  bool turns_directions() const override { return false; }  // its facet normals are recomputed

  DocumentFiles write(const Vertices& P, const NormalRotations&, const CompanionNames&) const override {
    if (binary_) check_fits_float32(Mesh{P, triangles_});
    ByteEdits edits;
    const CoordinateText text = CoordinateText::of_points(P);
    for (std::size_t f = 0; f < facet_count_; ++f) {
      const auto& corners = facet_slots_[f];
      bool moved = false;
      for (const int s : corners) moved = moved || P.row(s) != positions_.row(s);
      if (!moved) continue;
      Eigen::Vector3d c[3];
      for (int k = 0; k < 3; ++k) c[k] = P.row(corners[static_cast<std::size_t>(k)]).transpose();
      Eigen::Vector3d n = (c[1] - c[0]).cross(c[2] - c[0]);
      n = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
      const FacetPlaces places = binary_ ? binary_facet_places(f) : ascii_facets_[f];
      for (int a = 0; a < 3; ++a) {
        put(edits, places.normal[a], n[a], unit_vector_text());
        for (int k = 0; k < 3; ++k) put(edits, places.corner[k][a], c[k][a], text);
      }
    }
    return main_file_only(edits.empty() ? bytes_ : edits.apply(bytes_));
  }

 private:
  void put(ByteEdits& edits, ByteSpan span, double value, const CoordinateText& text) const {
    edits.replace(span, binary_ ? float_bytes(value) : text(value));
  }

  void read_binary(MeshBuilder& builder) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes_.data() + 80, 4);
    builder.reserve(count, count, bytes_.size());
    corners_.reserve(9ull * count);
    for (std::uint32_t t = 0; t < count; ++t) {
      builder.tick();
      const FacetPlaces places = binary_facet_places(t);
      for (const auto& corner : places.corner)
        for (const ByteSpan& span : corner) {
          float v;
          std::memcpy(&v, bytes_.data() + span.begin, 4);
          corners_.push_back(v);
        }
    }
    facet_count_ = count;
  }

  ByteSpan number_span(TextCursor& cursor, MeshBuilder& builder, double& value, const char* what) {
    cursor.skip_blanks();
    const std::size_t at = cursor.position();
    if (!cursor.read_number(value)) builder.fail(line_label(cursor.line()), what);
    return {at, cursor.position()};
  }

  void expect(TextCursor& cursor, MeshBuilder& builder, std::string_view word) {
    cursor.skip_whitespace_and_comments(0);
    const std::string_view got = cursor.token();
    if (got != word)
      builder.fail(line_label(cursor.line()),
                   "expected '" + std::string(word) + "' but found '" + std::string(got.substr(0, 20)) + "'");
  }

  void read_ascii(MeshBuilder& builder) {
    TextCursor cursor(bytes_);
    expect(cursor, builder, "solid");
    cursor.next_line();
    while (true) {
      builder.tick();
      cursor.skip_whitespace_and_comments(0);
      if (cursor.at_end()) builder.fail("", "the file ends without 'endsolid' (truncated?)");
      const std::size_t line = cursor.line();
      const std::string_view word = cursor.token();
      if (word == "endsolid") break;
      if (word != "facet") builder.fail(line_label(line), "expected 'facet' or 'endsolid'");
      FacetPlaces places;
      expect(cursor, builder, "normal");
      double ignored;
      for (auto& span : places.normal)
        span = number_span(cursor, builder, ignored, "a facet normal needs three numbers");
      expect(cursor, builder, "outer");
      expect(cursor, builder, "loop");
      for (auto& corner : places.corner) {
        expect(cursor, builder, "vertex");
        for (auto& span : corner) {
          double v;
          span = number_span(cursor, builder, v, "a vertex needs three numbers");
          corners_.push_back(v);
        }
      }
      expect(cursor, builder, "endloop");
      expect(cursor, builder, "endfacet");
      ascii_facets_.push_back(places);
    }
    if (ascii_facets_.empty()) builder.fail("", "the file has no triangles");
    facet_count_ = ascii_facets_.size();
  }

  // Corners at one exact position become one stored vertex (first appearance first).
  void weld(MeshBuilder& builder) {
    const auto n = static_cast<Eigen::Index>(corners_.size() / 3);
    const Eigen::Map<const Vertices> soup(corners_.data(), n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
      if (!soup.row(i).allFinite())
        builder.fail("triangle " + std::to_string(i / 3),
                     "a corner has a coordinate that is not a finite number (NaN or infinite)");
    Faces soup_faces(n / 3, 3);
    for (Eigen::Index f = 0; f < n / 3; ++f) soup_faces.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
    const WeldedSurface w = weld_positions(soup, soup_faces);
    for (Eigen::Index v = 0; v < w.mesh.V.rows(); ++v)
      builder.add_vertex(w.mesh.V(v, 0), w.mesh.V(v, 1), w.mesh.V(v, 2),
                         InputPlace::numbered("vertex", static_cast<std::size_t>(v)));
    facet_slots_.resize(facet_count_);
    for (std::size_t f = 0; f < facet_count_; ++f)
      for (int k = 0; k < 3; ++k)
        facet_slots_[f][static_cast<std::size_t>(k)] = w.vertex_of[3 * f + static_cast<std::size_t>(k)];
    for (const int f : w.face_of) {
      const long long corners[3] = {facet_slots_[static_cast<std::size_t>(f)][0],
                                    facet_slots_[static_cast<std::size_t>(f)][1],
                                    facet_slots_[static_cast<std::size_t>(f)][2]};
      builder.add_polygon(corners, 3, InputPlace::numbered("triangle", static_cast<std::size_t>(f)));
    }
    collapsed_ = w.collapsed_triangles;
    scene_welded_ = w.collapsed_triangles == 0 && w.duplicate_triangles == 0;  // then every vertex is on a triangle
    welded_ = w.welded_copies;
    take_scene(builder.finish());
    corners_.clear();
    corners_.shrink_to_fit();
  }

  std::string bytes_;
  bool binary_ = false;
  std::vector<double> corners_;  // while reading
  std::size_t facet_count_ = 0;
  std::vector<FacetPlaces> ascii_facets_;  // a binary file's follow from the index
  std::vector<std::array<int, 3>> facet_slots_;
  std::size_t collapsed_ = 0, welded_ = 0;

 public:
  std::size_t welded_corners() const { return welded_; }
};

}  // namespace

std::unique_ptr<MeshDocument> read_stl_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source) {
  return std::make_unique<StlDocument>(std::move(bytes), options, source);
}

}  // namespace meshmark
