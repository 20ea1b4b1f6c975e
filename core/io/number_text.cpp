#include "core/io/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>

#include "core/util/power_of_ten.hpp"

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

// `value` · 10^decimals rounded to the nearest integer, as to_chars rounds the exact binary value:
// the product is computed in doubles, within half an ulp of the exact one, so the rounding is
// certain unless the fraction lies within an ulp of one half. nullopt there, or beyond 2^53.
std::optional<std::uint64_t> scaled_integer(double value, int decimals) {
  if (decimals < 0 || decimals > kMaxExactPowerOfTen) return std::nullopt;
  const double y = std::abs(value) * power_of_ten(decimals);
  if (!(y < 9007199254740992.0)) return std::nullopt;        // 2^53: every integer below is a double
  const double whole = std::floor(y), fraction = y - whole;  // exact below 2^53
  std::uint64_t bits = 0;
  std::memcpy(&bits, &y, sizeof y);
  ++bits;  // the next double up (y is finite and not negative)
  double next = 0;
  std::memcpy(&next, &bits, sizeof next);
  const double ulp = next - y;
  if (std::abs(fraction - 0.5) <= ulp) return std::nullopt;
  return static_cast<std::uint64_t>(whole) + (fraction > 0.5 ? 1 : 0);
}

// The fixed text of ±n · 10^−decimals, without trailing zeros; "0" for zero whatever the sign.
std::size_t write_scaled(bool negative, std::uint64_t n, int decimals, char* out) {
  static constexpr char kPairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
      "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
      "8081828384858687888990919293949596979899";
  char digits[24];  // lowest first
  int count = 0;
  for (; n >= 100; n /= 100) {  // two digits a step
    const auto pair = static_cast<std::size_t>(2 * (n % 100));
    digits[count++] = kPairs[pair + 1];
    digits[count++] = kPairs[pair];
  }
  do digits[count++] = static_cast<char>('0' + n % 10), n /= 10;
  while (n > 0);
  while (count <= decimals) digits[count++] = '0';  // a zero before the point at least
  int last = 0;  // the lowest digit written: trailing zeros after the point are left out
  while (last < decimals && digits[last] == '0') ++last;
  std::size_t size = 0;
  const bool zero = count == decimals + 1 && last == decimals && digits[decimals] == '0';
  if (negative && !zero) out[size++] = '-';
  for (int i = count - 1; i >= last; --i) {
    if (i == decimals - 1) out[size++] = '.';
    out[size++] = digits[i];
  }
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
  std::size_t fixed_size = 0;
  bool exact = false;
  if (const auto n = scaled_integer(value, decimals_)) {  // by integer digits: 5.5 ms for the bunny, not 8.6
    fixed_size = write_scaled(value < 0, *n, decimals_, out);
    exact = static_cast<double>(*n) / power_of_ten(decimals_) == std::abs(value);  // as a reader rounds it
  } else {
    fixed_size = fixed_text(value, decimals_, out, kMaxChars);
    double back = 0;
    exact = fixed_size > 0 && std::from_chars(out, out + fixed_size, back).ec == std::errc() && back == value;
  }
  // A fixed text that does not read back to the value is shorter than the shortest text that
  // does, for any value from 1e-4 up (that text has more decimals, and its exponent form more
  // digits): the second conversion, half of a marked copy's writing, is then left out.
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
