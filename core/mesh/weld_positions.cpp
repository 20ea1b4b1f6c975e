#include "core/mesh/weld_positions.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <optional>
#include <tuple>

namespace meshmark {

namespace {

std::array<std::uint64_t, 3> position_bits(const Eigen::Ref<const Vertices>& V, Eigen::Index i) {
  std::array<std::uint64_t, 3> bits;
  for (int k = 0; k < 3; ++k) {
    const double x = V(i, k) + 0.0;  // -0.0 becomes +0.0
    std::memcpy(&bits[static_cast<std::size_t>(k)], &x, sizeof x);
  }
  return bits;
}

// Each used vertex's representative: the smallest index at its exact position. By sorting the
// positions (ties by index): O(n log n) whatever they are.
std::vector<int> representatives_by_sorting(const Eigen::Ref<const Vertices>& V, const std::vector<int>& used) {
  struct Position {
    std::array<std::uint64_t, 3> bits;
    int vertex;
    bool operator<(const Position& o) const {
      return std::tie(bits[0], bits[1], bits[2], vertex) < std::tie(o.bits[0], o.bits[1], o.bits[2], o.vertex);
    }
  };
  std::vector<Position> sorted;
  sorted.reserve(used.size());
  for (const int v : used) sorted.push_back({position_bits(V, v), v});
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> representative(static_cast<std::size_t>(V.rows()), -1);
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const auto v = static_cast<std::size_t>(sorted[i].vertex);
    const bool same = i > 0 && sorted[i].bits == sorted[i - 1].bits;
    representative[v] = same ? representative[static_cast<std::size_t>(sorted[i - 1].vertex)] : sorted[i].vertex;
  }
  return representative;
}

std::uint64_t position_hash(const std::array<std::uint64_t, 3>& bits) {
  std::uint64_t h = bits[0] * 0x9e3779b97f4a7c15ull;
  h ^= std::rotl(bits[1] * 0xc2b2ae3d27d4eb4full, 21);
  h ^= std::rotl(bits[2] * 0x165667b19e3779f9ull, 42);
  h ^= h >> 29;
  h *= 0xbf58476d1ce4e5b9ull;
  return h ^ (h >> 32);
}

// The same by a hash table over the positions, `used` in ascending order so that the first found
// is the smallest index: a fifth of the sort's time on a triangle soup. nullopt when the probes
// grow beyond a few per vertex (positions made to collide): the sort then bounds the cost.
std::optional<std::vector<int>> representatives_by_hashing(const Eigen::Ref<const Vertices>& V,
                                                           const std::vector<int>& used) {
  const std::size_t capacity = std::bit_ceil(2 * used.size() + 2), mask = capacity - 1;
  std::vector<int> slot(capacity, -1);
  std::vector<int> representative(static_cast<std::size_t>(V.rows()), -1);
  std::size_t probes = 0;
  const std::size_t budget = 8 * used.size() + 1024;
  for (const int v : used) {
    const auto bits = position_bits(V, v);
    for (std::size_t i = position_hash(bits) & mask;; i = (i + 1) & mask) {
      if (++probes > budget) return std::nullopt;
      if (slot[i] < 0) {
        slot[i] = v;
        representative[static_cast<std::size_t>(v)] = v;
        break;
      }
      if (position_bits(V, slot[i]) == bits) {
        representative[static_cast<std::size_t>(v)] = slot[i];
        break;
      }
    }
  }
  return representative;
}

std::vector<int> first_at_each_position(const Eigen::Ref<const Vertices>& V, const std::vector<int>& used) {
  if (auto hashed = representatives_by_hashing(V, used)) return std::move(*hashed);
  return representatives_by_sorting(V, used);
}

// Marks every triangle whose vertex set an earlier triangle already has. The triangles are counted
// into buckets by their smallest vertex, in face order: a bucket holds a handful, compared pairwise;
// the few large ones (a fan's hub) are sorted. Moving indices, not records, keeps it to a fifth of a
// sort of them all.
std::vector<char> repeated_triangles(const std::vector<int>& faces, std::size_t vertices) {
  const std::size_t n = faces.size() / 3;
  std::vector<std::array<int, 3>> sets(n);  // each triangle's vertices, ascending
  std::vector<std::size_t> bucket_end(vertices + 1, 0);
  for (std::size_t f = 0; f < n; ++f) {
    std::array<int, 3>& c = sets[f];
    c = {faces[3 * f], faces[3 * f + 1], faces[3 * f + 2]};
    if (c[0] > c[1]) std::swap(c[0], c[1]);  // three compare-exchanges sort three
    if (c[1] > c[2]) std::swap(c[1], c[2]);
    if (c[0] > c[1]) std::swap(c[0], c[1]);
    ++bucket_end[static_cast<std::size_t>(c[0]) + 1];
  }
  for (std::size_t v = 0; v < vertices; ++v) bucket_end[v + 1] += bucket_end[v];
  std::vector<std::uint32_t> order(n);  // triangles by smallest vertex, then by face
  for (std::size_t f = 0; f < n; ++f)
    order[bucket_end[static_cast<std::size_t>(sets[f][0])]++] = static_cast<std::uint32_t>(f);
  std::vector<char> repeated(n, 0);
  std::size_t begin = 0;
  for (std::size_t v = 0; v < vertices; begin = bucket_end[v++]) {
    const auto first = order.begin() + static_cast<std::ptrdiff_t>(begin),
               last = order.begin() + static_cast<std::ptrdiff_t>(bucket_end[v]);
    if (last - first <= 16) {
      for (auto i = first; i != last; ++i)
        repeated[*i] = std::any_of(first, i, [&](std::uint32_t earlier) { return sets[earlier] == sets[*i]; });
      continue;
    }
    std::sort(first, last,
              [&](std::uint32_t a, std::uint32_t b) { return std::tie(sets[a], a) < std::tie(sets[b], b); });
    for (auto i = first + 1; i != last; ++i) repeated[*i] = sets[*i] == sets[*(i - 1)];
  }
  return repeated;
}

// Keeps the first of every set of triangles over the same vertices.
void drop_repeated_triangles(WeldedSurface& s, std::vector<int>& faces) {
  const std::vector<char> repeated = repeated_triangles(faces, static_cast<std::size_t>(s.mesh.V.rows()));
  std::size_t kept = 0;
  for (std::size_t f = 0; f < repeated.size(); ++f) {
    if (repeated[f]) {
      ++s.duplicate_triangles;
      continue;
    }
    std::copy_n(faces.begin() + static_cast<long>(3 * f), 3, faces.begin() + static_cast<long>(3 * kept));
    s.face_of[kept++] = s.face_of[f];
  }
  faces.resize(3 * kept);
  s.face_of.resize(kept);
}

}  // namespace

WeldedSurface weld_positions(const Eigen::Ref<const Vertices>& V, const Faces& F) {
  const auto n = static_cast<std::size_t>(V.rows());
  // Stored vertices used by a triangle, in order of first use.
  std::vector<char> used(n, 0);
  std::vector<int> first_use;
  first_use.reserve(n);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(F(f, k));
      if (!used[v]) used[v] = 1;
    }
  for (std::size_t v = 0; v < n; ++v)
    if (used[v]) first_use.push_back(static_cast<int>(v));
  const std::vector<int> representative = first_at_each_position(V, first_use);
  WeldedSurface s;
  s.vertex_of.assign(n, -1);
  std::vector<double> coords;
  coords.reserve(3 * static_cast<std::size_t>(std::count_if(first_use.begin(), first_use.end(), [&](int v) {
                   return representative[static_cast<std::size_t>(v)] == v;
                 })));
  int next = 0;
  for (const int v : first_use) {  // in stored order: the surface keeps the file's vertex order
    const int r = representative[static_cast<std::size_t>(v)];
    if (r == v) {
      s.vertex_of[static_cast<std::size_t>(v)] = next++;
      coords.insert(coords.end(), {V(v, 0), V(v, 1), V(v, 2)});
    } else {
      ++s.welded_copies;
    }
  }
  for (const int v : first_use)
    s.vertex_of[static_cast<std::size_t>(v)] =
        s.vertex_of[static_cast<std::size_t>(representative[static_cast<std::size_t>(v)])];
  s.mesh.V = Eigen::Map<const Vertices>(coords.data(), next, 3);
  std::vector<int> faces;
  faces.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = s.vertex_of[static_cast<std::size_t>(F(f, 0))], b = s.vertex_of[static_cast<std::size_t>(F(f, 1))],
              c = s.vertex_of[static_cast<std::size_t>(F(f, 2))];
    if (a == b || b == c || a == c) {
      ++s.collapsed_triangles;
      continue;
    }
    faces.insert(faces.end(), {a, b, c});
    s.face_of.push_back(static_cast<int>(f));
  }
  drop_repeated_triangles(s, faces);
  s.mesh.F = Eigen::Map<const Faces>(faces.data(), static_cast<Eigen::Index>(faces.size() / 3), 3);
  return s;
}

WeldedSurface already_welded(Mesh mesh) {
  WeldedSurface s;
  s.vertex_of.resize(static_cast<std::size_t>(mesh.V.rows()));
  std::iota(s.vertex_of.begin(), s.vertex_of.end(), 0);
  s.face_of.resize(static_cast<std::size_t>(mesh.F.rows()));
  std::iota(s.face_of.begin(), s.face_of.end(), 0);
  s.mesh = std::move(mesh);
  return s;
}

Vertices stored_positions(const WeldedSurface& surface, const Vertices& surface_V, const Vertices& stored_V) {
  Vertices out = stored_V;
  for (Eigen::Index v = 0; v < out.rows(); ++v)
    if (const int w = surface.vertex_of.at(static_cast<std::size_t>(v)); w >= 0) out.row(v) = surface_V.row(w);
  return out;
}

}  // namespace meshmark
