// STL, binary (80-byte header, count, 50 bytes per triangle) and ASCII (`solid ... facet normal
// ... outer loop vertex x y z ...`). STL has no shared vertices: corners are welded by exact
// position, numbered in order of first appearance, so writing and re-reading keeps the order.

#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>

#include "core/io/mesh_builder.hpp"
#include "core/io/readers.hpp"
#include "core/io/text_cursor.hpp"

namespace meshmark {

namespace {

struct PositionKey {
  double x, y, z;
  bool operator==(const PositionKey& o) const {
    return std::memcmp(this, &o, sizeof(PositionKey)) == 0;
  }
};

struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t bits[3];
    std::memcpy(bits, &k, sizeof(bits));
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::uint64_t b : bits) h = (h ^ b) * 0xbf58476d1ce4e5b9ull, h ^= h >> 31;
    return static_cast<std::size_t>(h);
  }
};

// Welds triangle corners that share an exact position into one vertex.
class Welder {
 public:
  explicit Welder(MeshBuilder& builder) : builder_(builder) {}

  void add_triangle(const double corners[3][3], const std::string& where) {
    long long indices[3];
    for (int c = 0; c < 3; ++c) {
      // +0.0 so that -0.0 and 0.0 weld together.
      const PositionKey key{corners[c][0] + 0.0, corners[c][1] + 0.0, corners[c][2] + 0.0};
      const auto [it, inserted] = index_.try_emplace(key, static_cast<long long>(builder_.vertex_count()));
      if (inserted) builder_.add_vertex(key.x, key.y, key.z, where);
      else ++welded_;
      indices[c] = it->second;
    }
    builder_.add_polygon(indices, 3, where);
  }
  std::size_t welded() const { return welded_; }

 private:
  MeshBuilder& builder_;
  std::unordered_map<PositionKey, long long, PositionHash> index_;
  std::size_t welded_ = 0;
};

bool looks_binary(std::string_view bytes) {
  if (bytes.size() < 84) return false;
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);  // STL is little endian; so are our targets
  return 84 + 50ull * count == bytes.size();
}

ReadResult read_binary(std::string_view bytes, MeshBuilder& builder) {
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  builder.reserve(count, count, bytes.size());
  Welder welder(builder);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + 84 + 50ull * t + 12;  // skip the normal
    double corners[3][3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) {
        float v;
        std::memcpy(&v, record + 12 * c + 4 * k, 4);
        corners[c][k] = v;
      }
    welder.add_triangle(corners, "triangle " + std::to_string(t));
  }
  ReadResult result = builder.finish();
  result.stl_corners_welded = welder.welded();
  return result;
}

void expect(TextCursor& cursor, MeshBuilder& builder, std::string_view word) {
  cursor.skip_whitespace_and_comments(0);
  const std::string_view got = cursor.token();
  if (got != word)
    builder.fail(line_label(cursor.line()), "expected '" + std::string(word) + "' but found '" +
                                                std::string(got.substr(0, 20)) + "'");
}

ReadResult read_ascii(std::string_view bytes, MeshBuilder& builder) {
  TextCursor cursor(bytes);
  expect(cursor, builder, "solid");
  cursor.next_line();
  Welder welder(builder);
  while (true) {
    cursor.skip_whitespace_and_comments(0);
    if (cursor.at_end()) builder.fail("", "the file ends without 'endsolid' (truncated?)");
    const std::size_t line = cursor.line();
    const std::string_view word = cursor.token();
    if (word == "endsolid") break;
    if (word != "facet") builder.fail(line_label(line), "expected 'facet' or 'endsolid'");
    cursor.next_line();  // the normal is recomputed from the corners, never trusted
    expect(cursor, builder, "outer");
    expect(cursor, builder, "loop");
    double corners[3][3];
    for (auto& corner : corners) {
      expect(cursor, builder, "vertex");
      for (double& c : corner)
        if (!cursor.read_number(c)) builder.fail(line_label(cursor.line()), "a vertex needs three numbers");
    }
    expect(cursor, builder, "endloop");
    expect(cursor, builder, "endfacet");
    welder.add_triangle(corners, line_label(line));
  }
  if (builder.face_count() == 0) builder.fail("", "the file has no triangles");
  ReadResult result = builder.finish();
  result.stl_corners_welded = welder.welded();
  return result;
}

}  // namespace

ReadResult read_stl(std::string_view bytes, const ReadOptions& options, std::string_view source) {
  MeshBuilder builder(options, source);
  if (looks_binary(bytes)) return read_binary(bytes, builder);
  if (bytes.substr(0, 5) == "solid") return read_ascii(bytes, builder);
  if (bytes.size() >= 84)
    builder.fail("", "not an STL file: binary STL must be 84 + 50 × (triangle count) bytes long, "
                     "and ASCII STL must start with 'solid'");
  builder.fail("", "not an STL file: too short (" + std::to_string(bytes.size()) + " bytes)");
}

}  // namespace meshmark
