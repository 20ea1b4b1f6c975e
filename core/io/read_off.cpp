// OFF: a header `OFF` (also COFF, NOFF, CNOFF, STOFF...), optional on the same line as the counts
// `V F E`, then V lines `x y z [extra]` and F lines `n i1 ... in [colour]`, 0-based. `#` starts
// a comment.

#include <string>
#include <vector>

#include "core/io/mesh_builder.hpp"
#include "core/io/readers.hpp"
#include "core/io/text_cursor.hpp"

namespace meshmark {

namespace {

bool is_off_keyword(std::string_view token) {
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return false;
  return token.substr(0, token.size() - 3).find_first_not_of("STCN") == std::string_view::npos;
}

void next_record(TextCursor& cursor) {
  cursor.next_line();
  cursor.skip_whitespace_and_comments('#');
}

}  // namespace

ReadResult read_off(std::string_view bytes, const ReadOptions& options, std::string_view source) {
  MeshBuilder builder(options, source);
  TextCursor cursor(bytes);
  cursor.skip_whitespace_and_comments('#');
  const std::string_view keyword = cursor.token();
  if (!is_off_keyword(keyword))
    builder.fail(line_label(cursor.line()), "an OFF file must start with 'OFF' (found '" +
                                                std::string(keyword.substr(0, 20)) + "')");
  if (cursor.at_line_end('#')) next_record(cursor);

  long long nv = 0, nf = 0, ne = 0;
  if (!cursor.read_number(nv) || !cursor.read_number(nf) || nv < 0 || nf < 0)
    builder.fail(line_label(cursor.line()), "expected the counts 'vertices faces edges'");
  if (!cursor.at_line_end('#') && !cursor.read_number(ne))
    builder.fail(line_label(cursor.line()), "expected the edge count after the face count");
  builder.reserve(static_cast<std::size_t>(nv), static_cast<std::size_t>(nf), cursor.remaining());

  for (long long i = 0; i < nv; ++i) {
    next_record(cursor);
    if (cursor.at_end())
      builder.fail("", "file ends after " + std::to_string(i) + " of " + std::to_string(nv) +
                           " vertices (truncated?)");
    double xyz[3];
    for (double& c : xyz)
      if (!cursor.read_number(c))
        builder.fail(line_label(cursor.line()), "vertex " + std::to_string(i) + " needs three numbers x y z");
    builder.add_vertex(xyz[0], xyz[1], xyz[2], line_label(cursor.line()));
  }
  std::vector<long long> corners;
  for (long long i = 0; i < nf; ++i) {
    next_record(cursor);
    if (cursor.at_end())
      builder.fail("", "file ends after " + std::to_string(i) + " of " + std::to_string(nf) +
                           " faces (truncated?)");
    long long n = 0;
    if (!cursor.read_number(n) || n < 0)
      builder.fail(line_label(cursor.line()), "face " + std::to_string(i) + " must start with its vertex count");
    if (static_cast<std::size_t>(n) > cursor.remaining())
      builder.fail(line_label(cursor.line()), "face " + std::to_string(i) + " claims " + std::to_string(n) +
                                                  " vertices, more than the file holds");
    corners.resize(static_cast<std::size_t>(n));
    for (long long& c : corners)
      if (!cursor.read_number(c))
        builder.fail(line_label(cursor.line()), "face " + std::to_string(i) + " has fewer indices than its count " +
                                                    std::to_string(n));
    builder.add_polygon(corners.data(), corners.size(), line_label(cursor.line()));
  }
  if (nf == 0) builder.fail("", "the file has no faces");
  return builder.finish();
}

}  // namespace meshmark
