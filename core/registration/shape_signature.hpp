#pragma once
// A few numbers that say what a surface looks like whatever its pose, scale, sampling or vertex
// order: how far apart random points of it lie (Osada's D2 distribution, distances over their
// mean) and how its spread divides among its principal axes. Comparing them short-lists, among
// many originals, the few a suspect may be a copy of, before the full detection on each.

#include <array>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

inline constexpr int kSignatureBins = 32;

struct ShapeSignature {
  std::array<double, kSignatureBins> distances{};  ///< share of point pairs per bin of distance ÷ mean, over [0, 3)
  std::array<double, 2> spread_ratios{};           ///< second and third principal spread ÷ the first
};

/// Deterministic; the same for a moved, turned, scaled, reordered or remeshed copy up to sampling.
ShapeSignature shape_signature(const Mesh& mesh);

/// 0 for the same shape; grows as the shapes differ (at most 4).
double signature_distance(const ShapeSignature& a, const ShapeSignature& b);

/// As stored: the bins, then the ratios. from_values throws std::invalid_argument for another length.
std::vector<double> signature_values(const ShapeSignature& signature);
ShapeSignature signature_from_values(const std::vector<double>& values);

}  // namespace meshmark
