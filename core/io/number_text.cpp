#include "core/io/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace meshmark {

namespace {

template <typename T>
std::string shortest_text(T value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

/// `value` to `decimals` decimals, without trailing zeros; empty when it does not fit.
std::string fixed_text(double value, int decimals) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::fixed, decimals);
  if (result.ec != std::errc()) return {};
  std::string text(buffer, result.ptr);
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
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

std::string CoordinateText::operator()(double value) const {
  std::string shortest = shortest_text(value);
  if (decimals_ < 0 || !std::isfinite(value)) return shortest;
  std::string fixed = fixed_text(value, decimals_);
  return !fixed.empty() && fixed.size() < shortest.size() ? fixed : shortest;
}

}  // namespace meshmark
