#include "core/attacks/round_digits.hpp"

#include <cmath>
#include <stdexcept>

#include "core/util/power_of_ten.hpp"

namespace meshmark {

namespace {

double rounded(double x, int digits) {
  if (x == 0 || !std::isfinite(x)) return x;
  const int exponent = static_cast<int>(std::floor(std::log10(std::abs(x))));
  const int n = digits - 1 - exponent;
  // x · 10^n, or x / 10^−n where 10^−n is exact and 10^n would not be.
  if (n >= 0) {
    const double scale = power_of_ten(n);
    return std::round(x * scale) / scale;
  }
  const double scale = power_of_ten(-n);
  return std::round(x / scale) * scale;
}

}  // namespace

void round_digits_in_place(Vertices& V, int digits) {
  if (digits < 1 || digits > 17) throw std::invalid_argument("significant digits must be in 1..17");
  V = V.unaryExpr([digits](double x) { return rounded(x, digits); });
}

Mesh round_digits(const Mesh& mesh, int digits) {
  Mesh out = mesh;
  round_digits_in_place(out.V, digits);
  return out;
}

}  // namespace meshmark
