// PLY as a document, ASCII and binary (little and big endian): the `vertex` element's x, y, z and
// the `face` element's `vertex_indices` (or `vertex_index`) list are read; every other element and
// property is kept. Written back with the same header, elements, properties, types and encoding:
// only the x, y, z of moved vertices (in their own type) and their turned nx, ny, nz change.
// Triangle strips are refused.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/io/byte_edits.hpp"
#include "core/io/number_text.hpp"
#include "core/io/document_readers.hpp"
#include "core/io/mesh_builder.hpp"
#include "core/io/text_cursor.hpp"

namespace meshmark {

namespace {

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::optional<Scalar> parse_scalar(std::string_view name) {
  if (name == "char" || name == "int8") return Scalar::int8;
  if (name == "uchar" || name == "uint8") return Scalar::uint8;
  if (name == "short" || name == "int16") return Scalar::int16;
  if (name == "ushort" || name == "uint16") return Scalar::uint16;
  if (name == "int" || name == "int32") return Scalar::int32;
  if (name == "uint" || name == "uint32") return Scalar::uint32;
  if (name == "float" || name == "float32") return Scalar::float32;
  if (name == "double" || name == "float64") return Scalar::float64;
  return std::nullopt;
}

std::size_t scalar_bytes(Scalar s) {
  switch (s) {
    case Scalar::int8:
    case Scalar::uint8:
      return 1;
    case Scalar::int16:
    case Scalar::uint16:
      return 2;
    case Scalar::int32:
    case Scalar::uint32:
    case Scalar::float32:
      return 4;
    case Scalar::float64:
      return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  Scalar type = Scalar::float32;
  bool is_list = false;
  Scalar count_type = Scalar::uint8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Encoding { ascii, binary_le, binary_be };

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;
  std::size_t comments = 0;
};

Header parse_header(std::string_view bytes, MeshBuilder& builder) {
  Header header;
  TextCursor cursor(bytes);
  if (cursor.token() != "ply") builder.fail("line 1", "a PLY file must start with 'ply'");
  cursor.next_line();
  bool have_format = false;
  while (true) {
    if (cursor.at_end()) builder.fail("header", "the header has no 'end_header' line (truncated?)");
    const std::size_t line = cursor.line();
    const std::string_view keyword = cursor.token();
    if (keyword == "format") {
      const std::string_view f = cursor.token();
      if (f == "ascii") header.encoding = Encoding::ascii;
      else if (f == "binary_little_endian") header.encoding = Encoding::binary_le;
      else if (f == "binary_big_endian") header.encoding = Encoding::binary_be;
      else builder.fail(line_label(line), "unknown PLY format '" + std::string(f.substr(0, 40)) + "'");
      have_format = true;
    } else if (keyword == "element") {
      Element element;
      element.name = std::string(cursor.token());
      if (!cursor.read_number(element.count))
        builder.fail(line_label(line), "element '" + element.name.substr(0, 40) + "' needs a count");
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) builder.fail(line_label(line), "a property before any element");
      Property property;
      const std::string_view type = cursor.token();
      if (type == "list") {
        property.is_list = true;
        const auto count_type = parse_scalar(cursor.token());
        const auto item_type = parse_scalar(cursor.token());
        if (!count_type || !item_type) builder.fail(line_label(line), "unknown list types");
        property.count_type = *count_type;
        property.type = *item_type;
      } else {
        const auto scalar = parse_scalar(type);
        if (!scalar) builder.fail(line_label(line), "unknown property type '" + std::string(type.substr(0, 40)) + "'");
        property.type = *scalar;
      }
      property.name = std::string(cursor.token());
      header.elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      cursor.next_line();
      header.body_offset = cursor.position();
      break;
    } else if (keyword == "comment" || keyword == "obj_info") {
      ++header.comments;
    } else if (!keyword.empty()) {
      builder.fail(line_label(line), "unexpected header line '" + std::string(keyword.substr(0, 20)) + "'");
    }
    cursor.next_line();
  }
  if (!have_format) builder.fail("header", "no 'format' line");
  return header;
}

// Where a vertex's three scalars (x, y, z, or a normal's) sit in the file: their bytes (binary)
// or tokens (ASCII). Their types are the properties', kept once per element (VertexPlaces).
using ScalarSpans = std::array<ByteSpan, 3>;

// Every vertex's places, and the type each axis has in every vertex.
struct VertexPlaces {
  std::vector<ScalarSpans> spans;
  std::array<Scalar, 3> types{Scalar::float32, Scalar::float32, Scalar::float32};
};

// Reads scalars from the binary body, in either byte order, never past the end.
class BinarySource {
 public:
  BinarySource(std::string_view bytes, std::size_t offset, bool big_endian)
      : bytes_(bytes), pos_(offset), big_endian_(big_endian) {}
  std::size_t remaining() const { return bytes_.size() - pos_; }
  std::size_t position() const { return pos_; }

  bool read(Scalar type, double& value) {
    const std::size_t n = scalar_bytes(type);
    if (remaining() < n) return false;
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + pos_, n);
    pos_ += n;
    if (big_endian_ != (std::endian::native == std::endian::big))
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(raw[i], raw[n - 1 - i]);
    value = decode(type, raw);
    return true;
  }

 private:
  static double decode(Scalar type, const unsigned char* raw) {
    switch (type) {
      case Scalar::int8:
        return static_cast<std::int8_t>(raw[0]);
      case Scalar::uint8:
        return raw[0];
      case Scalar::int16:
        return load<std::int16_t>(raw);
      case Scalar::uint16:
        return load<std::uint16_t>(raw);
      case Scalar::int32:
        return load<std::int32_t>(raw);
      case Scalar::uint32:
        return load<std::uint32_t>(raw);
      case Scalar::float32:
        return load<float>(raw);
      case Scalar::float64:
        return load<double>(raw);
    }
    return 0;
  }
  template <typename T>
  static double load(const unsigned char* raw) {
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return static_cast<double>(v);
  }

  std::string_view bytes_;
  std::size_t pos_;
  bool big_endian_;
};

// Reads scalars as whitespace-separated tokens of the ASCII body.
class AsciiSource {
 public:
  AsciiSource(std::string_view bytes, std::size_t offset) : cursor_(bytes) { cursor_.skip_to(offset); }
  std::size_t remaining() const { return cursor_.remaining(); }
  std::size_t position() const { return cursor_.position(); }
  bool read(Scalar, double& value) {
    cursor_.skip_whitespace_and_comments(0);
    return cursor_.read_number(value);
  }
  std::size_t token_start() {
    cursor_.skip_whitespace_and_comments(0);
    return cursor_.position();
  }

 private:
  TextCursor cursor_;
};

bool is_face_list(const Property& p) { return p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index"); }

int axis_of(const std::string& name, const char* a, const char* b, const char* c) {
  return name == a ? 0 : name == b ? 1 : name == c ? 2 : -1;
}

// Encodes `value` as `type` in the given byte order; false if the type cannot hold it.
bool encode(Scalar type, double value, bool big_endian, std::string& out) {
  unsigned char raw[8];
  const auto integer = [&](auto tag, double lo, double hi) {
    using T = decltype(tag);
    const double r = std::nearbyint(value);
    if (!(r >= lo && r <= hi)) return false;
    const T v = static_cast<T>(r);
    std::memcpy(raw, &v, sizeof(T));
    return true;
  };
  bool ok = true;
  switch (type) {
    case Scalar::int8:
      ok = integer(std::int8_t{}, -128, 127);
      break;
    case Scalar::uint8:
      ok = integer(std::uint8_t{}, 0, 255);
      break;
    case Scalar::int16:
      ok = integer(std::int16_t{}, -32768, 32767);
      break;
    case Scalar::uint16:
      ok = integer(std::uint16_t{}, 0, 65535);
      break;
    case Scalar::int32:
      ok = integer(std::int32_t{}, -2147483648.0, 2147483647.0);
      break;
    case Scalar::uint32:
      ok = integer(std::uint32_t{}, 0, 4294967295.0);
      break;
    case Scalar::float32: {
      if (!(std::abs(value) <= std::numeric_limits<float>::max())) return false;
      const float f = static_cast<float>(value);
      std::memcpy(raw, &f, 4);
      break;
    }
    case Scalar::float64:
      std::memcpy(raw, &value, 8);
      break;
  }
  if (!ok) return false;
  const std::size_t n = scalar_bytes(type);
  if (big_endian != (std::endian::native == std::endian::big))
    for (std::size_t i = 0; i < n / 2; ++i) std::swap(raw[i], raw[n - 1 - i]);
  out.assign(reinterpret_cast<const char*>(raw), n);
  return true;
}

class PlyDocument : public MeshDocument {
 public:
  PlyDocument(std::string bytes, const DocumentReadOptions& options, const std::string& source)
      : MeshDocument(MeshFormat::ply), bytes_(std::move(bytes)) {
    MeshBuilder builder(options.limits, source);
    header_ = parse_header(bytes_, builder);
    check_elements(builder, bytes_.size() - header_.body_offset);
    keeps_places_ = options.for_writing;
    stores_normals_ = keeps_places_ && vertex_normals_declared();
    if (header_.encoding == Encoding::ascii) {
      AsciiSource ascii(bytes_, header_.body_offset);
      read_body(ascii, builder);
    } else {
      BinarySource binary(bytes_, header_.body_offset, header_.encoding == Encoding::binary_be);
      read_body(binary, builder);
    }
    if (!keeps_places_) std::string().swap(bytes_);  // read: nothing will be written back from them
    take_scene(builder.finish());
  }

  std::vector<DocumentPart> parts() const override {
    std::vector<DocumentPart> parts;
    for (const Element& e : header_.elements) {
      if (e.name != "vertex") continue;
      DocumentPart p;
      p.name = std::string(header_.encoding == Encoding::ascii ? "ascii" : "binary") + " vertex element";
      p.stored_vertices = static_cast<std::size_t>(e.count);
      p.triangles = static_cast<std::size_t>(triangles_.rows());
      for (const Property& prop : e.properties)
        if (prop.name != "x" && prop.name != "y" && prop.name != "z") p.attributes.push_back(prop.name);
      parts.push_back(std::move(p));
    }
    return parts;
  }

  bool turns_directions() const override { return !normals_.empty(); }

  DocumentFiles write(const Vertices& P, const NormalRotations& rotations, const CompanionNames&) const override {
    if (!keeps_places_) throw std::logic_error("a PLY document read only to be read cannot be written back");
    ByteEdits edits;
    const bool big_endian = header_.encoding == Encoding::binary_be;
    const CoordinateText text = CoordinateText::of_points(P);
    // Vertex v's three values at `places`, as the file stores them.
    const auto put = [&](const VertexPlaces& places, std::size_t v, const Eigen::Vector3d& values, const char* what,
                         const CoordinateText& as_text) {
      for (std::size_t k = 0; k < 3; ++k) {
        const Scalar type = places.types[k];
        const double value = values[static_cast<Eigen::Index>(k)];
        if (header_.encoding == Encoding::ascii) {
          edits.replace(places.spans[v][k],
                        type == Scalar::float32 ? number_text(static_cast<float>(value)) : as_text(value));
          continue;
        }
        std::string raw;
        if (!encode(type, value, big_endian, raw))
          throw MeshIoError("vertex " + std::to_string(v) + ": its new " + what + " " + std::to_string(value) +
                            " does not fit the file's property type");
        edits.replace(places.spans[v][k], std::move(raw));
      }
    };
    for (Eigen::Index v = 0; v < P.rows(); ++v) {
      const auto i = static_cast<std::size_t>(v);
      if (P.row(v) != positions_.row(v)) put(coordinates_, i, P.row(v).transpose(), "coordinate", text);
      if (!normals_.empty() && !rotations.empty() && rotations[i].w() != 1.0 && has_normal_[i])
        put(normal_places_, i, rotations[i] * normals_[i], "normal", unit_vector_text());
    }
    return main_file_only(edits.empty() ? bytes_ : edits.apply(bytes_));
  }

 private:
  void check_elements(MeshBuilder& builder, std::size_t body_bytes) const {
    bool vertex = false, face = false;
    for (const Element& e : header_.elements) {
      if (e.name == "tristrips")
        builder.fail("header", "triangle strips ('tristrips') are not supported; convert to a face list");
      std::set<std::string_view> names;
      for (const Property& p : e.properties)
        if (!names.insert(p.name).second)
          builder.fail("header", "element '" + e.name.substr(0, 40) + "' has two properties named '" +
                                     p.name.substr(0, 40) + "'");
      if ((e.name == "vertex" && vertex) || (e.name == "face" && face))
        builder.fail("header", "two elements named '" + e.name + "'");
      if (e.name == "vertex") {
        vertex = true;
        int found[3] = {0, 0, 0};
        for (const Property& p : e.properties)
          if (const int k = axis_of(p.name, "x", "y", "z"); !p.is_list && k >= 0) ++found[k];
        if (found[0] != 1 || found[1] != 1 || found[2] != 1)
          builder.fail("header", "the vertex element needs properties x, y and z");
      }
      if (e.name == "face") {
        face = true;
        bool list = false;
        for (const Property& p : e.properties) list = list || is_face_list(p);
        if (!list) builder.fail("header", "the face element needs a 'vertex_indices' list");
      }
    }
    if (!vertex || !face) builder.fail("header", "a mesh needs both a 'vertex' and a 'face' element");
    // Every item of an element with properties takes at least a byte per property: a count the
    // body cannot hold is refused before any loop runs.
    for (const Element& e : header_.elements) {
      if (e.properties.empty()) continue;
      std::uint64_t min_bytes = 0;
      for (const Property& p : e.properties)
        min_bytes += header_.encoding == Encoding::ascii ? 1 : scalar_bytes(p.is_list ? p.count_type : p.type);
      if (e.count > body_bytes / min_bytes)
        builder.fail("header", "element '" + e.name.substr(0, 40) + "' claims " + std::to_string(e.count) +
                                   " items, more than the " + std::to_string(body_bytes) + " bytes of data can hold");
    }
    std::uint64_t nv = 0, nf = 0;
    for (const Element& e : header_.elements) {
      if (e.name == "vertex") nv = e.count;
      if (e.name == "face") nf = e.count;
    }
    builder.reserve(nv, nf, body_bytes);
  }

  // Whether the vertex element declares a normal (nx, ny, nz as floats): only then are the places
  // of normals kept, which otherwise would more than double the reader's memory per vertex.
  bool vertex_normals_declared() const {
    for (const Element& e : header_.elements) {
      if (e.name != "vertex") continue;
      int found = 0;
      for (const Property& p : e.properties)
        if (!p.is_list && axis_of(p.name, "nx", "ny", "nz") >= 0 &&
            (p.type == Scalar::float32 || p.type == Scalar::float64))
          ++found;
      return found == 3;
    }
    return false;
  }

  template <typename Source>
  std::size_t start_of_next(Source& source) {
    if constexpr (std::is_same_v<Source, AsciiSource>) return source.token_start();
    else return source.position();
  }

  // Room for the vertex element's places, whose types it fixes. A binary body holds a vertex's
  // scalars per vertex (check_elements checks the count against its size); an ASCII vertex takes
  // at least two bytes (a character and a separator) per property, so no more can be there. Grown
  // by doubling instead, the places were copied at every doubling.
  template <typename Source>
  void reserve_vertex_places(const Element& vertex, const Source& source) {
    for (const Property& p : vertex.properties) {
      if (p.is_list) continue;
      if (const int k = axis_of(p.name, "x", "y", "z"); k >= 0)
        coordinates_.types[static_cast<std::size_t>(k)] = p.type;
      if (const int k = axis_of(p.name, "nx", "ny", "nz"); k >= 0)
        normal_places_.types[static_cast<std::size_t>(k)] = p.type;
    }
    std::uint64_t count = vertex.count;
    if constexpr (std::is_same_v<Source, AsciiSource>)
      count = std::min<std::uint64_t>(count, source.remaining() / (2 * vertex.properties.size()) + 1);
    const auto n = static_cast<std::size_t>(count);
    coordinates_.spans.reserve(n);
    if (!stores_normals_) return;
    normal_places_.spans.reserve(n);
    normals_.reserve(n);
    has_normal_.reserve(n);
  }

  template <typename Source>
  void read_body(Source& source, MeshBuilder& builder) {
    std::vector<long long> corners;
    for (const Element& element : header_.elements) {
      const bool is_vertex = element.name == "vertex";
      const bool is_face = element.name == "face";
      if (element.properties.empty()) continue;  // its items hold nothing to read
      if (is_vertex && keeps_places_) reserve_vertex_places(element, source);
      for (std::uint64_t i = 0; i < element.count; ++i) {
        builder.tick();
        const InputPlace where = InputPlace::numbered(element.name, i);
        double xyz[3] = {0, 0, 0}, n[3] = {0, 0, 0};
        ScalarSpans coordinate{}, normal{};
        int normal_parts = 0;
        for (const Property& p : element.properties) {
          double value = 0;
          if (!p.is_list) {
            const std::size_t begin = start_of_next(source);
            if (!source.read(p.type, value))
              builder.fail(
                  where, "the file ends or holds a non-number in property '" + p.name.substr(0, 40) + "' (truncated?)");
            if (!is_vertex) continue;
            const ByteSpan place{begin, source.position()};
            if (const int k = axis_of(p.name, "x", "y", "z"); k >= 0) {
              xyz[k] = value;
              coordinate[static_cast<std::size_t>(k)] = place;
            } else if (const int k2 = axis_of(p.name, "nx", "ny", "nz");
                       k2 >= 0 && (p.type == Scalar::float32 || p.type == Scalar::float64)) {
              n[k2] = value;
              normal[static_cast<std::size_t>(k2)] = place;
              ++normal_parts;
            }
            continue;
          }
          // Written so that NaN fails too: a list length must be a whole number the file can hold.
          if (!source.read(p.count_type, value) ||
              !(value >= 0 && value <= static_cast<double>(source.remaining()) && value == std::floor(value)))
            builder.fail(where, "bad or truncated list length in property '" + p.name.substr(0, 40) + "'");
          const auto count = static_cast<std::size_t>(value);
          const bool keep = is_face && is_face_list(p);
          if (keep) corners.resize(count);
          for (std::size_t k = 0; k < count; ++k) {
            if (!source.read(p.type, value))
              builder.fail(where, "the file ends inside the list '" + p.name.substr(0, 40) + "' (truncated?)");
            if (!keep) continue;
            if (!(value == std::floor(value) && std::abs(value) < 1e15))
              builder.fail(where, "a vertex index that is not a whole number");
            corners[k] = static_cast<long long>(value);
          }
          if (keep) builder.add_polygon(corners.data(), corners.size(), where);
        }
        if (!is_vertex) continue;
        builder.add_vertex(xyz[0], xyz[1], xyz[2], where);
        if (!keeps_places_) continue;
        coordinates_.spans.push_back(coordinate);
        if (!stores_normals_) continue;
        normal_places_.spans.push_back(normal);
        normals_.emplace_back(n[0], n[1], n[2]);
        has_normal_.push_back(normal_parts == 3);
      }
    }
    if (std::find(has_normal_.begin(), has_normal_.end(), true) == has_normal_.end()) {
      normals_.clear();
      normal_places_.spans.clear();
    }
  }

  std::string bytes_;
  Header header_;
  VertexPlaces coordinates_, normal_places_;
  std::vector<Eigen::Vector3d> normals_;
  std::vector<bool> has_normal_;
  bool keeps_places_ = true;
  bool stores_normals_ = false;
};

}  // namespace

std::unique_ptr<MeshDocument> read_ply_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source) {
  return std::make_unique<PlyDocument>(std::move(bytes), options, source);
}

}  // namespace meshmark
