#pragma once
// Point location in the spherical image of a mesh: which triangle of a bijective spherical map
// holds a point of the sphere, with its weights. The ray from the centre through the point meets
// exactly one flat triangle (a, b, c) of the image; where it meets it gives the gnomonic
// barycentric coordinates, the same the grid uses.

#include <memory>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/spatial/aabb_tree.hpp"

namespace meshmark {

struct SurfaceLocation {
  int face = 0;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
};

class SphericalMeshLocator {
 public:
  /// `S` (unit vectors) and `F` must outlive the locator.
  SphericalMeshLocator(const Vertices& S, const Faces& F);

  /// The triangle holding unit vector p. Never fails: near round-off it falls back to the
  /// triangle nearest the point.
  SurfaceLocation locate(const Eigen::Vector3d& p) const;

 private:
  const Vertices& S_;
  const Faces& F_;
  AabbTree tree_;
};

/// Locates many points (rows of P, unit vectors), on `threads` threads (0: the hardware's).
std::vector<SurfaceLocation> locate_all(const SphericalMeshLocator& locator, const Vertices& P, int threads = 0);

/// Σ bary_k · values.row(F(face, k)) for each location: #locations × values.cols().
Eigen::MatrixXd interpolate_at(const Faces& F, const std::vector<SurfaceLocation>& locations,
                               const Eigen::MatrixXd& values, int threads = 0);

}  // namespace meshmark
