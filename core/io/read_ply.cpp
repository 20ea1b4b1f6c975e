// PLY, ASCII and binary (little and big endian). Reads the `vertex` element's x, y, z and the
// `face` element's `vertex_indices` (or `vertex_index`) list; every other element and property
// is skipped. Triangle strips are refused.

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "core/io/mesh_builder.hpp"
#include "core/io/readers.hpp"
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
    case Scalar::int8: case Scalar::uint8: return 1;
    case Scalar::int16: case Scalar::uint16: return 2;
    case Scalar::int32: case Scalar::uint32: case Scalar::float32: return 4;
    case Scalar::float64: return 8;
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
      else builder.fail(line_label(line), "unknown PLY format '" + std::string(f) + "'");
      have_format = true;
    } else if (keyword == "element") {
      Element element;
      element.name = std::string(cursor.token());
      if (!cursor.read_number(element.count))
        builder.fail(line_label(line), "element '" + element.name + "' needs a count");
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
        if (!scalar) builder.fail(line_label(line), "unknown property type '" + std::string(type) + "'");
        property.type = *scalar;
      }
      property.name = std::string(cursor.token());
      header.elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      cursor.next_line();
      header.body_offset = cursor.position();
      break;
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      builder.fail(line_label(line), "unexpected header line '" + std::string(keyword.substr(0, 20)) + "'");
    }
    cursor.next_line();
  }
  if (!have_format) builder.fail("header", "no 'format' line");
  return header;
}

// Reads scalars from the binary body, in either byte order, never past the end.
class BinarySource {
 public:
  BinarySource(std::string_view bytes, bool big_endian) : bytes_(bytes), big_endian_(big_endian) {}
  std::size_t remaining() const { return bytes_.size() - pos_; }

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
      case Scalar::int8: return static_cast<std::int8_t>(raw[0]);
      case Scalar::uint8: return raw[0];
      case Scalar::int16: return load<std::int16_t>(raw);
      case Scalar::uint16: return load<std::uint16_t>(raw);
      case Scalar::int32: return load<std::int32_t>(raw);
      case Scalar::uint32: return load<std::uint32_t>(raw);
      case Scalar::float32: return load<float>(raw);
      case Scalar::float64: return load<double>(raw);
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
  bool big_endian_;
  std::size_t pos_ = 0;
};

// Reads scalars as whitespace-separated tokens of the ASCII body.
class AsciiSource {
 public:
  explicit AsciiSource(std::string_view bytes) : cursor_(bytes) {}
  std::size_t remaining() const { return cursor_.remaining(); }
  bool read(Scalar, double& value) {
    cursor_.skip_whitespace_and_comments(0);
    return cursor_.read_number(value);
  }

 private:
  TextCursor cursor_;
};

bool is_face_list(const Property& p) {
  return p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index");
}

template <typename Source>
void read_body(Source& source, const Header& header, MeshBuilder& builder) {
  std::vector<long long> corners;
  for (const Element& element : header.elements) {
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    if (element.properties.empty()) continue;  // its items hold nothing to read
    for (std::uint64_t i = 0; i < element.count; ++i) {
      builder.tick();
      const std::string where = element.name + " " + std::to_string(i);
      double xyz[3] = {0, 0, 0};
      for (const Property& p : element.properties) {
        double value = 0;
        if (!p.is_list) {
          if (!source.read(p.type, value))
            builder.fail(where, "the file ends or holds a non-number in property '" + p.name + "' (truncated?)");
          if (is_vertex && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z')
            xyz[p.name[0] - 'x'] = value;
          continue;
        }
        // Written so that NaN fails too: a list length must be a whole number the file can hold.
        if (!source.read(p.count_type, value) ||
            !(value >= 0 && value <= static_cast<double>(source.remaining()) && value == std::floor(value)))
          builder.fail(where, "bad or truncated list length in property '" + p.name + "'");
        const auto n = static_cast<std::size_t>(value);
        const bool keep = is_face && is_face_list(p);
        if (keep) corners.resize(n);
        for (std::size_t k = 0; k < n; ++k) {
          if (!source.read(p.type, value))
            builder.fail(where, "the file ends inside the list '" + p.name + "' (truncated?)");
          if (!keep) continue;
          if (!(value == std::floor(value) && std::abs(value) < 1e15))
            builder.fail(where, "a vertex index that is not a whole number");
          corners[k] = static_cast<long long>(value);
        }
        if (keep) builder.add_polygon(corners.data(), corners.size(), where);
      }
      if (is_vertex) builder.add_vertex(xyz[0], xyz[1], xyz[2], where);
    }
  }
}

void check_elements(const Header& header, MeshBuilder& builder, std::size_t body_bytes) {
  const Encoding encoding = header.encoding;
  bool vertex = false, face = false;
  for (const Element& e : header.elements) {
    if (e.name == "tristrips")
      builder.fail("header", "triangle strips ('tristrips') are not supported; convert to a face list");
    if (e.name == "vertex") {
      vertex = true;
      int found = 0;
      for (const Property& p : e.properties)
        if (!p.is_list && (p.name == "x" || p.name == "y" || p.name == "z")) ++found;
      if (found != 3) builder.fail("header", "the vertex element needs properties x, y and z");
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
  for (const Element& e : header.elements) {
    if (e.properties.empty()) continue;
    std::uint64_t min_bytes = 0;
    for (const Property& p : e.properties)
      min_bytes += encoding == Encoding::ascii ? 1 : scalar_bytes(p.is_list ? p.count_type : p.type);
    if (e.count > body_bytes / min_bytes)
      builder.fail("header", "element '" + e.name.substr(0, 40) + "' claims " + std::to_string(e.count) +
                                 " items, more than the " + std::to_string(body_bytes) + " bytes of data can hold");
  }
  std::uint64_t nv = 0, nf = 0;
  for (const Element& e : header.elements) {
    if (e.name == "vertex") nv = e.count;
    if (e.name == "face") nf = e.count;
  }
  if (nv > body_bytes || nf > body_bytes)
    builder.fail("header", "the header claims " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                               " faces, more than the " + std::to_string(body_bytes) + " bytes of data can hold");
  builder.reserve(nv, nf, body_bytes);
}

}  // namespace

ReadResult read_ply(std::string_view bytes, const ReadOptions& options, std::string_view source) {
  MeshBuilder builder(options, source);
  const Header header = parse_header(bytes, builder);
  const std::string_view body = bytes.substr(header.body_offset);
  check_elements(header, builder, body.size());
  if (header.encoding == Encoding::ascii) {
    AsciiSource ascii(body);
    read_body(ascii, header, builder);
  } else {
    BinarySource binary(body, header.encoding == Encoding::binary_be);
    read_body(binary, header, builder);
  }
  return builder.finish();
}

}  // namespace meshmark
