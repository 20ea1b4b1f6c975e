#pragma once
// The pictures an evidence report shows: the original, the suspect laid over it as the detector
// aligned it, and both together, so a reader sees that the two are the same shape.

#include <string>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct Picture {
  std::string caption;
  std::string png;
};

/// `suspect` already in the original's coordinates. From the front: the original (grey), the
/// suspect (orange), both; then both from the side.
std::vector<Picture> alignment_pictures(const Mesh& original, const Mesh& suspect, int size);

}  // namespace meshmark
