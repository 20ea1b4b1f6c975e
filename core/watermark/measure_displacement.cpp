#include "core/watermark/measure_displacement.hpp"

namespace meshmark {

Displacement measure_displacement(const AabbTree& suspect_tree, const Vertices& points, const Vertices& normals,
                                  double diagonal, const DisplacementOptions& options) {
  const double radius = options.search_radius * diagonal;
  Displacement d;
  d.t = Eigen::VectorXd::Zero(points.rows());
  d.found.assign(static_cast<std::size_t>(points.rows()), 0);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i), n = normals.row(i);
    if (auto hit = suspect_tree.nearest_crossing(p, n, radius)) {
      d.t[i] = hit->t;
      d.found[i] = 1;
    } else if (auto near = suspect_tree.closest_point(p, options.closest_fallback * radius)) {
      d.t[i] = (near->point - p).dot(n);
      d.found[i] = 1;
    } else {
      ++d.missing;
    }
  }
  return d;
}

}  // namespace meshmark
