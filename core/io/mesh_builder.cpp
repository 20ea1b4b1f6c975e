#include "core/io/mesh_builder.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace meshmark {

std::string line_label(std::size_t line) { return "line " + std::to_string(line); }

std::string InputPlace::words() const {
  return number_ == kNoNumber ? std::string(words_) : std::string(words_) + " " + std::to_string(number_);
}

MeshBuilder::MeshBuilder(const ReadOptions& options, std::string_view source_name)
    : options_(options), source_(source_name) {}

void MeshBuilder::reserve(std::size_t vertices, std::size_t faces, std::size_t available_bytes) {
  // Never trust a header: at most one vertex or face per 2 bytes of input can exist.
  const std::size_t cap = available_bytes / 2 + 1;
  coords_.reserve(3 * std::min({vertices, cap, options_.max_vertices}));
  faces_.reserve(3 * std::min({faces, cap, options_.max_faces}));
}

void MeshBuilder::fail(const InputPlace& where, const std::string& message) const {
  std::string text = source_;
  if (const std::string words = where.words(); !words.empty()) text += ": " + words;
  throw MeshIoError(text + ": " + message);
}

void MeshBuilder::fail_limit(const InputPlace& where, const std::string& message) const {
  std::string text = source_;
  if (const std::string words = where.words(); !words.empty()) text += ": " + words;
  throw MeshLimitError(text + ": " + message);
}

void MeshBuilder::add_vertex(double x, double y, double z, const InputPlace& where) {
  tick();
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
    fail(where, "vertex " + std::to_string(vertex_count()) +
                    " has a coordinate that is not a finite number (NaN or infinite)");
  if (std::max({std::abs(x), std::abs(y), std::abs(z)}) > kMaxCoordinate)
    fail(where,
         "vertex " + std::to_string(vertex_count()) + " has a coordinate beyond ±1e30, more than meshmark handles");
  if (vertex_count() >= options_.max_vertices)
    fail_limit(where, "more than " + std::to_string(options_.max_vertices) + " vertices (the limit for one mesh)");
  coords_.insert(coords_.end(), {x, y, z});
}

void MeshBuilder::add_polygon(const long long* indices, std::size_t count, const InputPlace& where) {
  if (count < 3)
    fail(where, "face " + std::to_string(face_count()) + " has " + std::to_string(count) +
                    " vertices; a face needs at least 3");
  tick();
  const long long n = static_cast<long long>(vertex_count());
  for (std::size_t i = 0; i < count; ++i)
    if (indices[i] < 0 || indices[i] >= n)
      fail(where, "face refers to vertex " + std::to_string(indices[i]) + " (0-based), but only " + std::to_string(n) +
                      " vertices are defined");
  // Distinct corners: pairwise for small polygons, by sorting for large ones (n log n).
  std::optional<long long> repeated;
  if (count <= 16) {
    for (std::size_t i = 0; i < count && !repeated; ++i)
      for (std::size_t k = 0; k < i; ++k)
        if (indices[k] == indices[i]) repeated = indices[i];
  } else {
    sorted_corners_.assign(indices, indices + count);
    std::sort(sorted_corners_.begin(), sorted_corners_.end());
    const auto at = std::adjacent_find(sorted_corners_.begin(), sorted_corners_.end());
    if (at != sorted_corners_.end()) repeated = *at;
  }
  if (repeated)
    fail(where, "face repeats vertex " + std::to_string(*repeated) + " (0-based); a face needs distinct vertices");
  if (face_count() + (count - 2) > options_.max_faces)
    fail_limit(where, "more than " + std::to_string(options_.max_faces) + " faces (the limit for one mesh)");
  if (count > 3) ++polygons_triangulated_;
  for (std::size_t i = 1; i + 1 < count; ++i)
    faces_.insert(faces_.end(),
                  {static_cast<int>(indices[0]), static_cast<int>(indices[i]), static_cast<int>(indices[i + 1])});
}

ReadResult MeshBuilder::finish() {
  if (vertex_count() == 0) fail("", "the file has no vertices");
  if (face_count() == 0) fail("", "the file has no faces");
  ReadResult result;
  const auto nv = static_cast<Eigen::Index>(vertex_count());
  const auto nf = static_cast<Eigen::Index>(face_count());
  result.mesh.V = Eigen::Map<const Vertices>(coords_.data(), nv, 3);
  result.mesh.F = Eigen::Map<const Faces>(faces_.data(), nf, 3);
  result.polygons_triangulated = polygons_triangulated_;
  return result;
}

}  // namespace meshmark
