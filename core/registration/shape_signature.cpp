#include "core/registration/shape_signature.hpp"

#include <cmath>
#include <stdexcept>

#include "core/mesh/surface_moments.hpp"
#include "core/metrics/compare_meshes.hpp"

namespace meshmark {

namespace {

constexpr std::size_t kSamples = 768;  // every pair of them: 294,528 distances, a few milliseconds
constexpr double kLastBinEdge = 3.0;   // distances past three times the mean share the last bin

}  // namespace

ShapeSignature shape_signature(const Mesh& mesh) {
  ShapeSignature s;
  const Vertices points = sample_surface(mesh, kSamples);
  std::vector<double> distances;
  distances.reserve(kSamples * (kSamples - 1) / 2);
  double sum = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (Eigen::Index j = i + 1; j < points.rows(); ++j)
      sum += distances.emplace_back((points.row(i) - points.row(j)).norm());
  const double mean = sum / static_cast<double>(distances.size());
  if (!(mean > 0)) return s;  // a surface of no extent: nothing to tell apart
  for (const double d : distances) {
    const int bin = std::min(kSignatureBins - 1, static_cast<int>(d / mean / kLastBinEdge * kSignatureBins));
    s.distances[static_cast<std::size_t>(bin)] += 1.0 / static_cast<double>(distances.size());
  }
  const SurfaceMoments m = surface_moments(mesh);
  if (m.variances[0] > 0)
    s.spread_ratios = {std::sqrt(m.variances[1] / m.variances[0]), std::sqrt(m.variances[2] / m.variances[0])};
  return s;
}

double signature_distance(const ShapeSignature& a, const ShapeSignature& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.distances.size(); ++k) d += std::abs(a.distances[k] - b.distances[k]);
  for (std::size_t k = 0; k < a.spread_ratios.size(); ++k) d += std::abs(a.spread_ratios[k] - b.spread_ratios[k]);
  return d;
}

std::vector<double> signature_values(const ShapeSignature& s) {
  std::vector<double> values(s.distances.begin(), s.distances.end());
  values.insert(values.end(), s.spread_ratios.begin(), s.spread_ratios.end());
  return values;
}

ShapeSignature signature_from_values(const std::vector<double>& values) {
  ShapeSignature s;
  if (values.size() != s.distances.size() + s.spread_ratios.size())
    throw std::invalid_argument("a shape signature has " + std::to_string(s.distances.size() + s.spread_ratios.size()) +
                                " values, not " + std::to_string(values.size()));
  std::copy(values.begin(), values.begin() + kSignatureBins, s.distances.begin());
  std::copy(values.begin() + kSignatureBins, values.end(), s.spread_ratios.begin());
  return s;
}

}  // namespace meshmark
