#include "core/mesh/coordinate_precision.hpp"

#include <cstdio>

namespace meshmark {

std::optional<std::string> coordinate_precision_problem(const Vertices& V) {
  if (V.rows() < 2) return std::nullopt;
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const double reach = V.cwiseAbs().maxCoeff();
  if (diagonal == 0 || diagonal >= kMinExtentToReach * reach) return std::nullopt;
  char text[240];
  std::snprintf(text, sizeof text,
                "the mesh spans %.3g but lies %.3g from the origin: its coordinates keep too few digits of its "
                "shape; move it near the origin first",
                diagonal, reach);
  return std::string(text);
}

}  // namespace meshmark
