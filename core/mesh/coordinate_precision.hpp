#pragma once
// Whether a mesh's coordinates still hold its shape. A mesh far from the origin relative to its
// size (a 1 m part placed at 1e12) keeps only a few digits of its shape in doubles, and every
// sum, centroid and normal computed on it is noise; a watermark, whose displacements are about
// 1e-4 of the bounding-box diagonal, cannot live there.

#include <optional>
#include <string>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// The bounding-box diagonal must be at least this fraction of the largest coordinate's
/// magnitude (doubles then keep ~7 digits of the shape).
inline constexpr double kMinExtentToReach = 1e-9;

/// A sentence saying why the coordinates cannot hold the shape, or nullopt when they can.
/// An empty mesh or one of a single point has no shape to lose: nullopt.
std::optional<std::string> coordinate_precision_problem(const Vertices& V);

}  // namespace meshmark
