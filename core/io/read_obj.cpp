// Wavefront OBJ: `v x y z [w]` and `f a b c ...` with `a`, `a/t`, `a//n` or `a/t/n` corners;
// negative indices count back from the last vertex defined. Everything else (vt, vn, groups,
// materials, lines) is skipped.

#include <string>
#include <vector>

#include "core/io/mesh_builder.hpp"
#include "core/io/readers.hpp"
#include "core/io/text_cursor.hpp"

namespace meshmark {

namespace {

void read_vertex(TextCursor& cursor, MeshBuilder& builder) {
  double xyz[3];
  for (double& c : xyz)
    if (!cursor.read_number(c))
      builder.fail(line_label(cursor.line()), "a 'v' line needs three numbers x y z");
  builder.add_vertex(xyz[0], xyz[1], xyz[2], line_label(cursor.line()));
}

void read_face(TextCursor& cursor, MeshBuilder& builder, std::vector<long long>& corners) {
  corners.clear();
  const auto defined = static_cast<long long>(builder.vertex_count());
  while (!cursor.at_line_end('#')) {
    const std::string_view token = cursor.token();
    long long index = 0;
    if (!parse_leading_integer(token, index) || index == 0)
      builder.fail(line_label(cursor.line()),
                   "face corner '" + std::string(token) + "' is not a vertex index (1-based, or negative)");
    corners.push_back(index > 0 ? index - 1 : defined + index);
  }
  builder.add_polygon(corners.data(), corners.size(), line_label(cursor.line()));
}

}  // namespace

ReadResult read_obj(std::string_view bytes, const ReadOptions& options, std::string_view source) {
  MeshBuilder builder(options, source);
  TextCursor cursor(bytes);
  std::vector<long long> corners;
  while (!cursor.at_end()) {
    cursor.skip_blanks();
    const std::string_view keyword = cursor.token();
    if (keyword == "v") {
      read_vertex(cursor, builder);
    } else if (keyword == "f") {
      read_face(cursor, builder, corners);
    } else if (!keyword.empty() && keyword.front() != '#') {
      // Not a keyword we use (vt, vn, g, o, s, usemtl, ...): it must at least be text.
      for (char c : keyword)
        if (static_cast<unsigned char>(c) < 9 || c == 0x7f)
          builder.fail(line_label(cursor.line()), "binary data in an OBJ file (is it really OBJ?)");
    }
    cursor.next_line();
  }
  if (builder.face_count() == 0) builder.fail("", "no faces found (is this an OBJ mesh file?)");
  return builder.finish();
}

}  // namespace meshmark
