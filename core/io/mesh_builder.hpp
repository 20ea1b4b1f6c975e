#pragma once
// Collects vertices and polygons while a parser reads a file, and checks each one as it comes:
// finite coordinates, indices in range, at least three distinct vertices per face.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/read_mesh.hpp"

namespace meshmark {

/// Where in a file an element stands, for an error message: words ("triangle 5") or a numbered
/// line, made into words only when an error names it (a label made for every element was a tenth
/// of reading an OBJ).
class InputPlace {
 public:
  InputPlace(std::string_view words) : words_(words) {}    // NOLINT: any text names a place
  InputPlace(const std::string& words) : words_(words) {}  // NOLINT
  InputPlace(const char* words) : words_(words) {}         // NOLINT
  /// "unit number"; `unit` is kept by reference.
  static InputPlace numbered(std::string_view unit, std::size_t number) {
    InputPlace place(unit);
    place.number_ = number;
    return place;
  }
  static InputPlace line(std::size_t number) { return numbered("line", number); }
  std::string words() const;

 private:
  std::string_view words_;
  std::size_t number_ = kNoNumber;
  static constexpr std::size_t kNoNumber = ~std::size_t{0};
};

class MeshBuilder {
 public:
  MeshBuilder(const ReadOptions& options, std::string_view source_name);

  /// Reserves room, clamped by what `available_bytes` of input could possibly hold.
  void reserve(std::size_t vertices, std::size_t faces, std::size_t available_bytes);

  void add_vertex(double x, double y, double z, const InputPlace& where);

  /// Adds a polygon of 0-based vertex indices; polygons above 3 vertices are fan-triangulated.
  void add_polygon(const long long* indices, std::size_t count, const InputPlace& where);

  std::size_t vertex_count() const { return coords_.size() / 3; }
  std::size_t face_count() const { return faces_.size() / 3; }

  /// Throws MeshIoError with the source name and location prepended.
  [[noreturn]] void fail(const InputPlace& where, const std::string& message) const;
  /// The same, as MeshLimitError (a limit of ReadOptions was reached).
  [[noreturn]] void fail_limit(const InputPlace& where, const std::string& message) const;

  /// Counts one unit of work (an element read or skipped) and polls the control now and then.
  void tick() {
    if (++ticks_ % 4096 == 0) poll(options_.control);
  }

  ReadResult finish();

 private:
  ReadOptions options_;
  std::string source_;
  std::vector<double> coords_;
  std::vector<int> faces_;
  std::size_t polygons_triangulated_ = 0;
  std::size_t ticks_ = 0;
  std::vector<long long> sorted_corners_;  // scratch for the duplicate check of large polygons
};

/// "line N" for error messages.
std::string line_label(std::size_t line);

}  // namespace meshmark
