// STL, binary (80-byte header, count, 50 bytes per triangle) and ASCII (`solid ... facet normal
// ... outer loop vertex x y z ...`). STL has no shared vertices: corners are welded by exact
// position, numbered in order of first appearance, so writing and re-reading keeps the order.

#include <cstdint>
#include <cstring>
#include <string>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/io/mesh_builder.hpp"
#include "core/io/readers.hpp"
#include "core/io/text_cursor.hpp"

namespace meshmark {

namespace {

// Collects triangle corners, then welds those at the same exact position into one vertex,
// numbered in order of first appearance. Sorting (not hashing) keeps the work n log n whatever
// the positions: no file can make every corner collide.
class Welder {
 public:
  /// `label` names a triangle's place in messages: "triangle" (its number) or "line" (its line).
  Welder(MeshBuilder& builder, std::string label) : builder_(builder), label_(std::move(label)) {}

  void add_triangle(const double corners[3][3], std::size_t place) {
    builder_.tick();
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k)
        if (!std::isfinite(corners[c][k]))
          builder_.fail(where(place), "a corner has a coordinate that is not a finite number (NaN or infinite)");
      // +0.0 so that -0.0 and 0.0 weld together.
      corners_.push_back({corners[c][0] + 0.0, corners[c][1] + 0.0, corners[c][2] + 0.0});
    }
    places_.push_back(place);
  }

  /// Hands the welded vertices and the triangles to the builder.
  std::size_t finish() {
    const std::size_t n = corners_.size();
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
    const auto key = [&](std::uint32_t i) {
      std::array<std::uint64_t, 3> bits;
      std::memcpy(bits.data(), corners_[i].data(), sizeof bits);
      return bits;
    };
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const auto ka = key(a), kb = key(b);
      return ka != kb ? ka < kb : a < b;
    });
    // Each corner's group is represented by its first appearance.
    std::vector<std::uint32_t> first(n);
    for (std::size_t i = 0; i < n; ++i)
      first[order[i]] = i > 0 && key(order[i]) == key(order[i - 1]) ? first[order[i - 1]] : order[i];
    std::vector<long long> vertex_of(n, -1);
    std::size_t welded = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (first[i] == i) {
        vertex_of[i] = static_cast<long long>(builder_.vertex_count());
        builder_.add_vertex(corners_[i][0], corners_[i][1], corners_[i][2], where(places_[i / 3]));
      } else {
        vertex_of[i] = vertex_of[first[i]];
        ++welded;
      }
    }
    for (std::size_t t = 0; t < n / 3; ++t) {
      const long long triangle[3] = {vertex_of[3 * t], vertex_of[3 * t + 1], vertex_of[3 * t + 2]};
      builder_.add_polygon(triangle, 3, where(places_[t]));
    }
    return welded;
  }

 private:
  std::string where(std::size_t place) const { return label_ + " " + std::to_string(place); }

  MeshBuilder& builder_;
  std::string label_;
  std::vector<std::array<double, 3>> corners_;
  std::vector<std::size_t> places_;
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
  Welder welder(builder, "triangle");
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + 84 + 50ull * t + 12;  // skip the normal
    double corners[3][3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) {
        float v;
        std::memcpy(&v, record + 12 * c + 4 * k, 4);
        corners[c][k] = v;
      }
    welder.add_triangle(corners, t);
  }
  const std::size_t welded = welder.finish();
  ReadResult result = builder.finish();
  result.stl_corners_welded = welded;
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
  Welder welder(builder, "line");
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
    welder.add_triangle(corners, line);
  }
  const std::size_t welded = welder.finish();
  if (builder.face_count() == 0) builder.fail("", "the file has no triangles");
  ReadResult result = builder.finish();
  result.stl_corners_welded = welded;
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
