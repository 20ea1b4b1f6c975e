#pragma once
// Distortion between two surfaces, as watermarking papers report it: the one-sided RMS and
// maximum distances from points sampled densely (uniformly by area, and at every vertex) on one
// surface to the other, both ways. MRMS is the larger RMS, Hausdorff the larger maximum; both
// are also given relative to A's bounding-box diagonal.

#include <cstddef>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct CompareOptions {
  std::size_t samples = 200000;  ///< points sampled on each surface (besides its vertices)
  int threads = 0;               ///< for the closest points (0: the hardware's); same result on any count
};

struct SurfaceDistance {
  double rms_ab = 0, rms_ba = 0;  ///< one-sided RMS distances, A's samples to B and back
  double max_ab = 0, max_ba = 0;
  double mrms = 0;       ///< max(rms_ab, rms_ba), in A's units
  double hausdorff = 0;  ///< max(max_ab, max_ba)
  double diagonal = 0;   ///< A's bounding-box diagonal
  double mrms_relative() const { return mrms / diagonal; }
  double hausdorff_relative() const { return hausdorff / diagonal; }
};

/// Deterministic (a fixed sampling sequence). Works on any triangle soups.
SurfaceDistance compare_meshes(const Mesh& a, const Mesh& b, const CompareOptions& options = {});

/// Points uniformly distributed by area on the surface (deterministic, stratified): n×3.
/// `faces`, if given, receives the face each point lies on.
Vertices sample_surface(const Mesh& mesh, std::size_t n, std::vector<int>* faces = nullptr);

/// sample_surface for several counts on one mesh: its face areas summed once (at millions of
/// faces, a registration summed them a few times over). Keeps a reference to `mesh`.
class SurfaceSampler {
 public:
  explicit SurfaceSampler(const Mesh& mesh);
  Vertices sample(std::size_t n, std::vector<int>* faces = nullptr) const;

 private:
  const Mesh& mesh_;
  std::vector<double> cumulative_;  ///< face areas summed in face order
};

}  // namespace meshmark
