#pragma once
// Flat-shaded pictures of meshes from a software z-buffer: what the evidence report shows of the
// original and of a suspect laid over it. No GPU, no window: the same bytes on every machine.

#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/render/image.hpp"

namespace meshmark {

/// An orthographic camera: it looks along `forward` with `up` pointing to the top of the picture.
struct View {
  Eigen::Vector3d forward = -Eigen::Vector3d::UnitZ();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
};

/// From the front (along -z) and from the side (along -x), y up: how glTF, OBJ and most tools
/// show a model, so the pictures look like what its owner knows.
std::vector<View> front_and_side_views();

struct Layer {
  const Mesh* mesh = nullptr;
  Rgb colour;
};

/// The layers drawn together in one picture of `size`×`size` pixels, framed on `frame` (default:
/// the first layer's vertices), so a suspect far off the original shows off its place. Nearer
/// surfaces hide farther ones; where two layers coincide both colours show, speckled.
Image render_layers(const std::vector<Layer>& layers, const View& view, int size, const Vertices* frame = nullptr);

}  // namespace meshmark
