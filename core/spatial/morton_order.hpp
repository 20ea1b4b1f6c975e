#pragma once
// Points in Z-order (Morton order) over their bounding box. Queries of a spatial tree made in this
// order touch the nodes the previous query touched, and the previous answer is a close bound: at
// millions of vertices, queries in file order spent most of their time waiting on memory.

#include <cstdint>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// The indices of `points` (#P×3) sorted by their Z-order key on a 2^21 lattice over the
/// points' bounding box (ties by index): a permutation of 0..#P−1.
std::vector<std::int64_t> morton_order(const Eigen::Ref<const Vertices>& points);

}  // namespace meshmark
