#include "core/attacks/draco_compress.hpp"

#include <stdexcept>
#include <string>

#include "core/io/draco_primitive.hpp"

namespace meshmark {

Mesh draco_compress(const Mesh& mesh, int bits) {
  if (bits < 1 || bits > 30)
    throw std::invalid_argument("Draco quantizes positions to 1..30 bits, not " + std::to_string(bits));
  return draco_decode_positions(draco_encode_positions(mesh, bits));
}

}  // namespace meshmark
