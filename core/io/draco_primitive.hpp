#pragma once
// A glTF primitive compressed with KHR_draco_mesh_compression (libdraco): decoded for reading,
// and re-encoded after its positions moved, with the quantization each attribute had.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace draco {
class Mesh;
}

namespace meshmark {

class DracoPrimitive {
 public:
  /// Decodes a Draco mesh; `position_id` is the POSITION attribute's unique id (the glTF
  /// extension's "attributes"). Throws MeshIoError when the bytes are not a Draco mesh with it.
  DracoPrimitive(std::string_view bytes, int position_id);
  ~DracoPrimitive();
  DracoPrimitive(DracoPrimitive&&) noexcept;

  /// #points × 3 positions, as decoded (the file's local space).
  const Vertices& positions() const { return positions_; }
  /// Triangles over the points.
  const Faces& faces() const { return faces_; }
  /// Quantization bits of the POSITION attribute (0: stored as floats).
  int position_bits() const;

  /// The Draco bitstream with the points at `positions` (#points × 3) and every attribute
  /// quantized as it was.
  std::string encode(const Vertices& positions) const;

 private:
  std::unique_ptr<draco::Mesh> mesh_;
  int position_attribute_ = -1;  // index among the mesh's attributes
  std::vector<int> bits_;        // per attribute: quantization bits, 0 for none
  Vertices positions_;
  Faces faces_;
};

/// A Draco mesh of `mesh` with positions quantized to `bits` and nothing else: what a leaker's
/// tool writes (for the attack that simulates it). Points are reordered by the encoder.
std::string draco_encode_positions(const Mesh& mesh, int bits);
/// Decodes a Draco mesh with only positions (as from draco_encode_positions).
Mesh draco_decode_positions(std::string_view bytes);

}  // namespace meshmark
