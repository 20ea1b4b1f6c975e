#include "core/mesh/edge_incidence.hpp"

#include <algorithm>
#include <cstdint>

namespace meshmark {

EdgeIncidence edge_incidence(const Faces& F) {
  struct HalfEdge {
    std::uint64_t key;  // (min << 32) | max
    int corner;         // 3 * face + k
    bool along;         // traversed from min to max
  };
  std::vector<HalfEdge> half(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(F(f, k)), b = static_cast<std::uint32_t>(F(f, (k + 1) % 3));
      const std::uint64_t lo = std::min(a, b), hi = std::max(a, b);
      half[3 * f + k] = {(lo << 32) | hi, static_cast<int>(3 * f + k), a < b};
    }
  std::sort(half.begin(), half.end(),
            [](const HalfEdge& x, const HalfEdge& y) { return x.key != y.key ? x.key < y.key : x.corner < y.corner; });

  EdgeIncidence result;
  result.face_edges.resize(F.rows(), 3);
  std::vector<int> ends;
  for (std::size_t i = 0; i < half.size();) {
    const int e = static_cast<int>(result.face_count.size());
    ends.push_back(static_cast<int>(half[i].key >> 32));
    ends.push_back(static_cast<int>(half[i].key & 0xffffffffu));
    int count = 0, along = 0;
    std::size_t j = i;
    for (; j < half.size() && half[j].key == half[i].key; ++j) {
      ++count;
      along += half[j].along ? 1 : 0;
      result.face_edges(half[j].corner / 3, half[j].corner % 3) = e;
    }
    result.face_count.push_back(count);
    result.along_count.push_back(along);
    i = j;
  }
  result.edges = Eigen::Map<const Edges>(ends.data(), static_cast<Eigen::Index>(ends.size() / 2), 2);
  return result;
}

}  // namespace meshmark
