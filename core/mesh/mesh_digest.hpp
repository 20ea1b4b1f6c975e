#pragma once

#include <string>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// SHA-256 (hex) of the geometry and connectivity: vertex count, face count, every coordinate
/// as an IEEE-754 double and every index as a 32-bit integer, all little-endian. Identifies a
/// model across machines, whatever file format it came in.
std::string mesh_digest(const Mesh& mesh);

}  // namespace meshmark
