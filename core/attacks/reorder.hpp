#pragma once
// Reordering attack: the same surface with vertices and faces listed in a random order (and each
// face's corners rotated), reproducible from a seed.

#include <cstdint>

#include "core/mesh/mesh.hpp"

namespace meshmark {

Mesh reorder(const Mesh& mesh, std::uint64_t seed);

}  // namespace meshmark
