#include "core/spatial/morton_order.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace meshmark {

namespace {

constexpr int kBitsPerAxis = 21;  // three axes in one 64-bit key

// The low 21 bits of x spread to every third bit.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= (std::uint64_t{1} << kBitsPerAxis) - 1;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

std::vector<std::int64_t> morton_order(const Eigen::Ref<const Vertices>& points) {
  const auto n = static_cast<std::size_t>(points.rows());
  std::vector<std::pair<std::uint64_t, std::int64_t>> keyed(n);
  if (n == 0) return {};
  const Eigen::RowVector3d lo = points.colwise().minCoeff(), extent = points.colwise().maxCoeff() - lo;
  const double cells = static_cast<double>((std::uint64_t{1} << kBitsPerAxis) - 1);
  const double scale = extent.maxCoeff() > 0 ? cells / extent.maxCoeff() : 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t key = 0;
    for (int k = 0; k < 3; ++k) {
      const double cell = (points(static_cast<Eigen::Index>(i), k) - lo[k]) * scale;
      const double kept = cell >= 0 ? std::min(cell, cells) : 0.0;  // a NaN coordinate goes to cell 0
      key |= spread_bits(static_cast<std::uint64_t>(kept)) << k;
    }
    keyed[i] = {key, static_cast<std::int64_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::int64_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace meshmark
