#include "core/render/alignment_pictures.hpp"

#include "core/render/rasterize.hpp"

namespace meshmark {

std::vector<Picture> alignment_pictures(const Mesh& original, const Mesh& suspect, int size) {
  const Rgb grey{170, 170, 178}, orange{235, 120, 30};
  const Layer original_layer{&original, grey}, suspect_layer{&suspect, orange};
  const std::vector<View> views = front_and_side_views();
  std::vector<Picture> out;
  out.push_back({"The original", encode_png(render_layers({original_layer}, views[0], size))});
  // Framed on the original: a suspect that did not align shows off its place.
  out.push_back({"The suspect, aligned to the original",
                 encode_png(render_layers({suspect_layer}, views[0], size, &original.V))});
  out.push_back({"Both: grey and orange speckle where the surfaces coincide",
                 encode_png(render_layers({original_layer, suspect_layer}, views[0], size))});
  out.push_back(
      {"Both, seen from the side", encode_png(render_layers({original_layer, suspect_layer}, views[1], size))});
  return out;
}

}  // namespace meshmark
