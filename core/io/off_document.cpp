// OFF as a document: a header `OFF` (also COFF, NOFF, CNOFF, STOFF...), optional on the same line
// as the counts `V F E`, then V lines `x y z [nx ny nz] [colour] [s t]` and F lines
// `n i1 ... in [colour]`, 0-based; `#` starts a comment. Written back byte for byte but the
// coordinates of moved vertices (and, for NOFF, their turned normals).

#include <array>
#include <string>
#include <vector>

#include "core/io/byte_edits.hpp"
#include "core/io/number_text.hpp"
#include "core/io/document_readers.hpp"
#include "core/io/mesh_builder.hpp"
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

class OffDocument : public MeshDocument {
 public:
  OffDocument(std::string bytes, const DocumentReadOptions& options, const std::string& source)
      : MeshDocument(MeshFormat::off), bytes_(std::move(bytes)) {
    parse(options, source);
  }

  std::vector<DocumentPart> parts() const override {
    DocumentPart p;
    p.name = "whole file";
    p.stored_vertices = static_cast<std::size_t>(positions_.rows());
    p.triangles = static_cast<std::size_t>(triangles_.rows());
    if (!normal_tokens_.empty()) p.attributes.push_back("normals");
    return {p};
  }

  bool turns_directions() const override { return !normal_tokens_.empty(); }

  DocumentFiles write(const Vertices& P, const NormalRotations& rotations, const CompanionNames&) const override {
    ByteEdits edits;
    const CoordinateText text = CoordinateText::of_points(P);
    char buffer[CoordinateText::kMaxChars];
    for (Eigen::Index v = 0; v < P.rows(); ++v) {
      const auto i = static_cast<std::size_t>(v);
      if (P.row(v) != positions_.row(v))
        for (int k = 0; k < 3; ++k)
          edits.replace(vertex_tokens_[i][static_cast<std::size_t>(k)], {buffer, text.write(P(v, k), buffer)});
      if (!normal_tokens_.empty() && !rotations.empty() && rotations[i].w() != 1.0) {
        const Eigen::Vector3d n = rotations[i] * normals_[i];
        for (int k = 0; k < 3; ++k)
          edits.replace(normal_tokens_[i][static_cast<std::size_t>(k)], unit_vector_text()(n[k]));
      }
    }
    return main_file_only(edits.empty() ? bytes_ : edits.apply(bytes_));
  }

 private:
  std::array<ByteSpan, 3> read_triple(TextCursor& cursor, MeshBuilder& builder, double* out, const std::string& what) {
    std::array<ByteSpan, 3> spans;
    for (int k = 0; k < 3; ++k) {
      cursor.skip_blanks();
      const std::size_t at = cursor.position();
      if (!cursor.read_number(out[k])) builder.fail(line_label(cursor.line()), what);
      spans[static_cast<std::size_t>(k)] = {at, cursor.position()};
    }
    return spans;
  }

  void parse(const DocumentReadOptions& options, const std::string& source) {
    MeshBuilder builder(options.limits, source);
    TextCursor cursor(bytes_);
    cursor.skip_whitespace_and_comments('#');
    const std::string_view keyword = cursor.token();
    if (!is_off_keyword(keyword))
      builder.fail(line_label(cursor.line()),
                   "an OFF file must start with 'OFF' (found '" + std::string(keyword.substr(0, 20)) + "')");
    const bool has_normals = keyword.substr(0, keyword.size() - 3).find('N') != std::string_view::npos;
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
        builder.fail("",
                     "file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices (truncated?)");
      double xyz[3];
      vertex_tokens_.push_back(
          read_triple(cursor, builder, xyz, "vertex " + std::to_string(i) + " needs three numbers x y z"));
      if (has_normals) {
        double n[3];
        normal_tokens_.push_back(
            read_triple(cursor, builder, n, "vertex " + std::to_string(i) + " needs a normal nx ny nz"));
        normals_.emplace_back(n[0], n[1], n[2]);
      }
      builder.add_vertex(xyz[0], xyz[1], xyz[2], InputPlace::line(cursor.line()));
    }
    std::vector<long long> corners;
    for (long long i = 0; i < nf; ++i) {
      next_record(cursor);
      if (cursor.at_end())
        builder.fail("", "file ends after " + std::to_string(i) + " of " + std::to_string(nf) + " faces (truncated?)");
      long long n = 0;
      if (!cursor.read_number(n) || n < 0)
        builder.fail(line_label(cursor.line()), "face " + std::to_string(i) + " must start with its vertex count");
      if (static_cast<std::size_t>(n) > cursor.remaining())
        builder.fail(line_label(cursor.line()), "face " + std::to_string(i) + " claims " + std::to_string(n) +
                                                    " vertices, more than the file holds");
      corners.resize(static_cast<std::size_t>(n));
      for (long long& c : corners)
        if (!cursor.read_number(c))
          builder.fail(line_label(cursor.line()),
                       "face " + std::to_string(i) + " has fewer indices than its count " + std::to_string(n));
      builder.add_polygon(corners.data(), corners.size(), InputPlace::line(cursor.line()));
    }
    if (nf == 0) builder.fail("", "the file has no faces");
    take_scene(builder.finish());
  }

  std::string bytes_;
  std::vector<std::array<ByteSpan, 3>> vertex_tokens_, normal_tokens_;
  std::vector<Eigen::Vector3d> normals_;
};

}  // namespace

std::unique_ptr<MeshDocument> read_off_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source) {
  return std::make_unique<OffDocument>(std::move(bytes), options, source);
}

}  // namespace meshmark
