#pragma once
// Sorting records whose order starts with a small integer key (a vertex index): counted into one
// bucket per key in O(n + keys), then each bucket sorted alone. A mesh's half-edges or triangles
// spread over its vertices leave a handful per bucket, where one comparison sort of them all was
// a large share of reading or validating a mesh.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace meshmark {

/// Sorts `items` as std::sort with `less` would, where `key(item)` is below `keys` and `less` orders
/// by it first (an item of a smaller key comes before). Stable within a key before the buckets'
/// sorts, so equal items keep no particular order, as with std::sort.
template <typename T, typename Key, typename Less>
void bucket_sort(std::vector<T>& items, std::size_t keys, Key key, Less less) {
  std::vector<std::size_t> start(keys + 1, 0);
  for (const T& item : items) ++start[key(item) + 1];
  for (std::size_t k = 0; k < keys; ++k) start[k + 1] += start[k];
  std::vector<T> sorted(items.size());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (const T& item : items) sorted[next[key(item)]++] = item;
  for (std::size_t k = 0; k < keys; ++k)
    if (start[k + 1] - start[k] > 1)
      std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(start[k]),
                sorted.begin() + static_cast<std::ptrdiff_t>(start[k + 1]), less);
  items = std::move(sorted);
}

/// Whether bucket_sort pays for `items` records over `keys` keys: keys far beyond the records
/// (indices of a sparse or hostile file) would cost more buckets than a comparison sort.
inline bool bucket_sort_pays(std::size_t items, std::size_t keys) { return keys <= 4 * items + 1024; }

}  // namespace meshmark
