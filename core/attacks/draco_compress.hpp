#pragma once
// Draco compression attack: the mesh encoded with Google's Draco (libdraco, as glTF pipelines
// compress with KHR_draco_mesh_compression) at a position quantization of `bits`, and decoded:
// positions rounded to a grid over the bounding box, points renumbered by the encoder.

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// `bits` in 1..30 (Draco's range); glTF tools use 11 to 16.
Mesh draco_compress(const Mesh& mesh, int bits);

}  // namespace meshmark
