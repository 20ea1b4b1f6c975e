#include "core/mesh/edge_incidence.hpp"

#include <algorithm>
#include <cstdint>

#include "core/util/bucket_sort.hpp"

namespace meshmark {

namespace {

struct HalfEdge {
  std::uint64_t key;  // edge_key
  int corner;         // 3 * face + k
  bool along;         // traversed from min to max
};

bool before(const HalfEdge& x, const HalfEdge& y) { return x.key != y.key ? x.key < y.key : x.corner < y.corner; }

// The half-edges in `before` order, bucketed by their smaller end (core/util/bucket_sort.hpp).
std::vector<HalfEdge> sorted_half_edges(const Faces& F) {
  std::vector<HalfEdge> half(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      half[3 * f + k] = {edge_key(a, b), static_cast<int>(3 * f + k), a < b};
    }
  const auto smaller_end = [](const HalfEdge& h) { return static_cast<std::size_t>(h.key >> 32); };
  const std::size_t keys = half.empty() ? 0 : smaller_end(*std::max_element(half.begin(), half.end(), before)) + 1;
  if (bucket_sort_pays(half.size(), keys)) bucket_sort(half, keys, smaller_end, before);
  else std::sort(half.begin(), half.end(), before);
  return half;
}

}  // namespace

EdgeIncidence edge_incidence(const Faces& F) {
  const std::vector<HalfEdge> half = sorted_half_edges(F);
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
