#pragma once
// Quantization attack: each coordinate rounded to one of 2^bits levels spanning the bounding box.

#include "core/mesh/mesh.hpp"

namespace meshmark {

Mesh quantize(const Mesh& mesh, int bits);

}  // namespace meshmark
