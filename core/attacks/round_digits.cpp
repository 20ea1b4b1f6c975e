#include "core/attacks/round_digits.hpp"

#include <cmath>
#include <stdexcept>

namespace meshmark {

namespace {

double rounded(double x, int digits) {
  if (x == 0 || !std::isfinite(x)) return x;
  const int exponent = static_cast<int>(std::floor(std::log10(std::abs(x))));
  const double scale = std::pow(10.0, digits - 1 - exponent);
  return std::round(x * scale) / scale;
}

}  // namespace

Mesh round_digits(const Mesh& mesh, int digits) {
  if (digits < 1 || digits > 17) throw std::invalid_argument("significant digits must be in 1..17");
  Mesh out = mesh;
  out.V = out.V.unaryExpr([digits](double x) { return rounded(x, digits); });
  return out;
}

}  // namespace meshmark
