#pragma once
// A glTF primitive compressed with KHR_draco_mesh_compression (libdraco): decoded for reading,
// and re-encoded after its positions moved, with the quantization each attribute had.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace draco {
class Mesh;
}

namespace meshmark {

/// What a Draco mesh stream says it holds, read from its first bytes: the decoder sizes its
/// tables by these counts, so a few kilobytes can claim (and would cost) gigabytes.
struct DracoDeclared {
  std::uint64_t vertices = 0;  ///< encoded vertices (edgebreaker: split vertices aside, bounded by faces)
  std::uint64_t faces = 0;
};
/// The counts of a triangle-mesh stream (sequential or edgebreaker, bitstream 1.x–2.2, metadata
/// skipped); none when the header cannot be read ahead (cut short, a point cloud, another method,
/// metadata nested over 32 deep or with an empty value, which libdraco refuses too).
std::optional<DracoDeclared> draco_declared(std::string_view bytes);

/// How much one Draco primitive may decode to.
struct DracoLimits {
  std::uint64_t vertices = UINT64_MAX, faces = UINT64_MAX;
};

class DracoPrimitive {
 public:
  /// Decodes a Draco mesh; `position_id` is the POSITION attribute's unique id (the glTF
  /// extension's "attributes"). Throws MeshLimitError, before decoding, when the stream declares
  /// more than `limits`; MeshIoError when its size cannot be read ahead or the bytes are not a
  /// Draco mesh with that attribute.
  DracoPrimitive(std::string_view bytes, int position_id, const DracoLimits& limits = {});
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
