#include "core/attacks/round_digits.hpp"

#include <cmath>
#include <stdexcept>

namespace meshmark {

namespace {

// 10^n: exact from a table where doubles hold it exactly (pow was most of a verification's
// re-save, which rounds every coordinate of a copy).
double power_of_ten(int n) {
  static constexpr double kExact[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  return n >= 0 && n <= 22 ? kExact[n] : std::pow(10.0, n);
}

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

Mesh round_digits(const Mesh& mesh, int digits) {
  if (digits < 1 || digits > 17) throw std::invalid_argument("significant digits must be in 1..17");
  Mesh out = mesh;
  out.V = out.V.unaryExpr([digits](double x) { return rounded(x, digits); });
  return out;
}

}  // namespace meshmark
