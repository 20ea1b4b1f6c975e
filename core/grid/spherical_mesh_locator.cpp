#include "core/grid/spherical_mesh_locator.hpp"

#include "core/grid/sphere_grid.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

SphericalMeshLocator::SphericalMeshLocator(const Vertices& S, const Faces& F) : S_(S), F_(F), tree_(S, F) {}

SurfaceLocation SphericalMeshLocator::locate(const Eigen::Vector3d& p) const {
  // Flat triangles with corners on the unit sphere lie inside the ball: the crossing has t ≤ 1.
  if (auto hit = tree_.first_hit(Eigen::Vector3d::Zero(), p, 0.0, 1.0 + 1e-9)) {
    const int f = hit->face;
    return {f, gnomonic_barycentric(p, S_.row(F_(f, 0)), S_.row(F_(f, 1)), S_.row(F_(f, 2)))};
  }
  const auto nearest = tree_.closest_point(p);  // a ray lost on a shared edge by round-off
  const int f = nearest->face;
  return {f, gnomonic_barycentric(p, S_.row(F_(f, 0)), S_.row(F_(f, 1)), S_.row(F_(f, 2)))};
}

std::vector<SurfaceLocation> locate_all(const SphericalMeshLocator& locator, const Vertices& P, int threads) {
  std::vector<SurfaceLocation> out(static_cast<std::size_t>(P.rows()));
  parallel_for(P.rows(), threads, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) out[i] = locator.locate(P.row(i));
  });
  return out;
}

Eigen::MatrixXd interpolate_at(const Faces& F, const std::vector<SurfaceLocation>& locations,
                               const Eigen::MatrixXd& values, int threads) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(locations.size()), values.cols());
  parallel_for(static_cast<std::int64_t>(locations.size()), threads, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      const auto& l = locations[i];
      out.row(i) = l.bary[0] * values.row(F(l.face, 0)) + l.bary[1] * values.row(F(l.face, 1)) +
                   l.bary[2] * values.row(F(l.face, 2));
    }
  });
  return out;
}

}  // namespace meshmark
