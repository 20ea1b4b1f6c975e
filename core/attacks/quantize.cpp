#include "core/attacks/quantize.hpp"

#include <cmath>
#include <stdexcept>

namespace meshmark {

Mesh quantize(const Mesh& mesh, int bits) {
  if (bits < 1 || bits > 30) throw std::invalid_argument("quantization bits must be in 1..30");
  const Eigen::RowVector3d lo = mesh.V.colwise().minCoeff(), hi = mesh.V.colwise().maxCoeff();
  const double levels = std::ldexp(1.0, bits) - 1;
  Mesh out = mesh;
  for (int k = 0; k < 3; ++k) {
    const double span = hi[k] - lo[k];
    if (span <= 0) continue;
    for (Eigen::Index v = 0; v < out.V.rows(); ++v)
      out.V(v, k) = lo[k] + std::round((out.V(v, k) - lo[k]) / span * levels) / levels * span;
  }
  return out;
}

}  // namespace meshmark
