#include "core/io/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>

namespace meshmark {

namespace {

template <typename T>
std::string shortest_text(T value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

/// `value` to `decimals` decimals into `out`, without trailing zeros; 0 when it does not fit.
std::size_t fixed_text(double value, int decimals, char* out, std::size_t capacity) {
  const auto result = std::to_chars(out, out + capacity, value, std::chars_format::fixed, decimals);
  if (result.ec != std::errc()) return 0;
  std::size_t size = static_cast<std::size_t>(result.ptr - out);
  if (std::string_view(out, size).find('.') != std::string_view::npos) {
    while (out[size - 1] == '0') --size;
    if (out[size - 1] == '.') --size;
  }
  if (std::string_view(out, size) == "-0") out[0] = '0', size = 1;
  return size;
}

std::size_t shortest(double value, char* out) {
  return static_cast<std::size_t>(std::to_chars(out, out + CoordinateText::kMaxChars, value).ptr - out);
}

}  // namespace

std::string number_text(double value) { return shortest_text(value); }
std::string number_text(float value) { return shortest_text(value); }

CoordinateText::CoordinateText(double extent) {
  const double quantum = 1e-7 * extent;
  if (!std::isfinite(quantum) || quantum <= 0) return;
  const double exponent = std::floor(std::log10(quantum));
  decimals_ = exponent >= 0 ? 0 : static_cast<int>(std::min(-exponent, 30.0));
}

CoordinateText CoordinateText::of_points(const Vertices& P) {
  if (P.rows() == 0) return CoordinateText(0);
  return CoordinateText((P.colwise().maxCoeff() - P.colwise().minCoeff()).norm());
}

std::size_t CoordinateText::write(double value, char* out) const {
  if (decimals_ < 0 || !std::isfinite(value)) return shortest(value, out);
  const std::size_t fixed_size = fixed_text(value, decimals_, out, kMaxChars);
  // A fixed text that does not read back to the value is shorter than the shortest text that
  // does, for any value from 1e-4 up (that text has more decimals, and its exponent form more
  // digits): the second conversion, half of a marked copy's writing, is then left out.
  double back = 0;
  const bool exact = fixed_size > 0 && std::from_chars(out, out + fixed_size, back).ec == std::errc() && back == value;
  if (fixed_size > 0 && !exact && std::abs(value) >= 1e-4) return fixed_size;
  char shortest_text[kMaxChars];
  const std::size_t shortest_size = shortest(value, shortest_text);
  if (fixed_size > 0 && fixed_size < shortest_size) return fixed_size;
  std::memcpy(out, shortest_text, shortest_size);
  return shortest_size;
}

std::string CoordinateText::operator()(double value) const {
  char buffer[kMaxChars];
  return std::string(buffer, write(value, buffer));
}

}  // namespace meshmark
