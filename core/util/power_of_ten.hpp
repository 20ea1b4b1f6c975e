#pragma once
// Powers of ten for decimal text and rounding: exact from a table where a double holds them.

#include <cmath>

namespace meshmark {

/// The largest n for which 10^n is exactly a double.
inline constexpr int kMaxExactPowerOfTen = 22;

/// 10^n: exact from a table for 0 ≤ n ≤ kMaxExactPowerOfTen (std::pow took most of rounding a
/// mesh's coordinates to digits), std::pow beyond.
inline double power_of_ten(int n) {
  static constexpr double kExact[kMaxExactPowerOfTen + 1] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                             1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                                             1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  return n >= 0 && n <= kMaxExactPowerOfTen ? kExact[n] : std::pow(10.0, n);
}

}  // namespace meshmark
