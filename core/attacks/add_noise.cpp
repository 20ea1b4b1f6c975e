#include "core/attacks/add_noise.hpp"

#include <stdexcept>

#include "core/util/keyed_random.hpp"

namespace meshmark {

NoiseReference parse_noise_reference(const std::string& name) {
  if (name == "bbox") return NoiseReference::bbox_diagonal;
  if (name == "centroid") return NoiseReference::centroid_distance;
  throw std::invalid_argument("unknown noise reference '" + name + "' (expected bbox or centroid)");
}

double noise_reference_length(const Mesh& mesh, NoiseReference reference) {
  if (reference == NoiseReference::bbox_diagonal)
    return (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  const Eigen::RowVector3d centroid = mesh.V.colwise().mean();
  return (mesh.V.rowwise() - centroid).rowwise().norm().mean();
}

Mesh add_noise(const Mesh& mesh, double amplitude_percent, NoiseReference reference, std::uint64_t seed) {
  if (amplitude_percent < 0) throw std::invalid_argument("the noise amplitude must not be negative");
  KeyedRandom random("attack", "noise/" + std::to_string(seed));
  const double a = amplitude_percent / 100.0 * noise_reference_length(mesh, reference);
  Mesh out = mesh;
  for (Eigen::Index v = 0; v < out.V.rows(); ++v)
    for (int k = 0; k < 3; ++k) out.V(v, k) += a * (2 * random.unit() - 1);
  return out;
}

}  // namespace meshmark
