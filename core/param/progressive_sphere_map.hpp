#pragma once
// A spherical map bijective by construction, as in Zhou et al. (2002) and Praun and Hoppe
// (2003): coarsen the mesh to a tetrahedron by half-edge collapses, place the tetrahedron on the
// sphere, then undo the collapses in reverse order, putting each re-inserted vertex strictly inside
// the spherical kernel of its one-ring (exact orientation tests), so that no triangle ever
// flips. After each doubling of the vertex count, and at the end, a fold-free descent of the
// stretch energy (core/param/spherical_stretch) spreads the sphere's area over the faces in
// proportion to the surface they stand for.

#include <functional>
#include <string>

#include "core/mesh/mesh.hpp"
#include "core/param/spherical_stretch.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

// The defaults are measured on the 18 genus-0 meshes of ../shared/meshes and its corpus, each also
// in three random vertex orders: every map bijective, 5th percentile of the area ratio at least
// 0.07 (see docs/method.md), at ~20 µs per vertex.
struct ProgressiveSphereMapOptions {
  int settle_steps = 12;       ///< descent steps of each re-inserted vertex alone (4: the worst p05 halves)
  int coarse_vertices = 1000;  ///< levels up to this many vertices are cheap: they get...
  int coarse_sweeps = 30;      ///< ... this many descent passes;
  int level_sweeps = 6;        ///< larger levels this many;
  int final_sweeps = 16;       ///< the whole mesh, with the true face shapes, this many;
  /// levels beyond this many vertices get their passes scaled by large_vertices / vertices, at
  /// least 2: a fine tessellation only needs local smoothing once the coarse levels have spread
  /// the area, and its grid is coarser than it (557k vertices: the map in 7.2 s instead of 9.1,
  /// the area ratio's p05 0.63 for 0.68; with all passes, 18 s and 0.73).
  int large_vertices = 100000;
  StretchDescentOptions descent;  ///< its `sweeps` is set per level from the above
  /// Called after each level's descent with the images so far and the level's faces (tests
  /// check every intermediate map is fold-free).
  std::function<void(const Vertices& S, const Faces& faces)> on_level;
};

struct ProgressiveSphereMap {
  Vertices S;  ///< #V×3 unit vectors
  std::size_t collapses = 0;
  int levels = 0;                    ///< refinement batches (each doubles the vertex count)
  std::size_t kernel_fallbacks = 0;  ///< splits whose vertex could not go to its ring's centroid
  std::size_t relaxations = 0;       ///< splits that needed their neighbourhood relaxed first
  double coarsen_seconds = 0, refine_seconds = 0, final_seconds = 0;
};

/// Maps a closed, 2-manifold, genus-0 mesh with faces wound outward onto the unit sphere. Every
/// intermediate map is fold-free; so is the result (the caller still proves it). Deterministic.
/// Reports progress as stage `stage` from `progress_from` to `progress_to`; polls `control`.
ProgressiveSphereMap progressive_sphere_map(const Vertices& V, const Faces& F,
                                            const ProgressiveSphereMapOptions& options = {},
                                            const JobControl* control = nullptr,
                                            const std::string& stage = "parameterize", double progress_from = 0,
                                            double progress_to = 1);

}  // namespace meshmark
