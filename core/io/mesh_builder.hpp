#pragma once
// Collects vertices and polygons while a parser reads a file, and checks each one as it comes:
// finite coordinates, indices in range, at least three distinct vertices per face.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/read_mesh.hpp"

namespace meshmark {

class MeshBuilder {
 public:
  MeshBuilder(const ReadOptions& options, std::string_view source_name);

  /// Reserves room, clamped by what `available_bytes` of input could possibly hold.
  void reserve(std::size_t vertices, std::size_t faces, std::size_t available_bytes);

  void add_vertex(double x, double y, double z, std::string_view where);

  /// Adds a polygon of 0-based vertex indices; polygons above 3 vertices are fan-triangulated.
  void add_polygon(const long long* indices, std::size_t count, std::string_view where);

  std::size_t vertex_count() const { return coords_.size() / 3; }
  std::size_t face_count() const { return faces_.size() / 3; }

  /// Throws MeshIoError with the source name and location prepended.
  [[noreturn]] void fail(std::string_view where, const std::string& message) const;
  /// The same, as MeshLimitError (a limit of ReadOptions was reached).
  [[noreturn]] void fail_limit(std::string_view where, const std::string& message) const;

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
