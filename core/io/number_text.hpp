#pragma once
// Numbers as text for the formats that store them so: as short as what they must keep.

#include <string>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// The shortest text that reads back to the same double (or float).
std::string number_text(double value);
std::string number_text(float value);

/// Coordinates of a shape as text, to a fixed number of decimals: the largest power of ten at
/// most 1e-7 of the shape's extent (its bounding box diagonal), so that a coordinate moves by at
/// most half of that — a thousandth of the faintest watermark — and a marked copy's file is
/// about as large as a 7-digit original's instead of growing by its doubles' 17 digits. A value
/// whose shortest round-trip text is shorter keeps it; without a usable extent every value does.
class CoordinateText {
 public:
  explicit CoordinateText(double extent);
  /// For the rows of P (x, y, z each): the diagonal of their bounding box.
  static CoordinateText of_points(const Vertices& P);
  std::string operator()(double value) const;
  /// The same text written to `out` (at least kMaxChars bytes); returns its length.
  static constexpr std::size_t kMaxChars = 64;
  std::size_t write(double value, char* out) const;
  void append(std::string& out, double value) const {
    char buffer[kMaxChars];
    out.append(buffer, write(value, buffer));
  }
  int decimals() const { return decimals_; }

 private:
  int decimals_ = -1;  // -1: shortest round-trip text only
};

/// Unit vectors (normals) to seven decimals.
inline const CoordinateText& unit_vector_text() {
  static const CoordinateText text(1.0);
  return text;
}

}  // namespace meshmark
