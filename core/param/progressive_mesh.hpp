#pragma once
// The coarsening half of a progressive mesh (Hoppe 1996), as Zhou et al. (2002) use it for
// spherical parameterization: half-edge collapses, shortest edge first, until a tetrahedron is
// left. Every collapse keeps the mesh a closed 2-manifold of genus 0 (the link condition and no
// vertex below valence 3: core/mesh/collapse_is_safe), so that undone in reverse order, as vertex
// splits, they rebuild the mesh one vertex at a time.

#include <array>
#include <functional>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct ProgressiveMesh {
  /// The four vertices left, and the tetrahedron's faces (wound like the input's).
  std::array<int, 4> base_vertices{};
  Faces base_faces;
  /// Collapse i merged vertex removed[i] into kept[i]. The removed vertex's one-ring at that
  /// moment is ring[ring_offsets[i] .. ring_offsets[i+1]), counter-clockwise seen from outside
  /// (faces wound outward), starting with kept[i].
  std::vector<int> removed, kept;
  std::vector<int> ring_offsets{0};
  std::vector<int> ring;

  std::size_t collapses() const { return removed.size(); }
};

/// Coarsens a closed, 2-manifold, genus-0, consistently oriented triangle mesh (#V ≥ 4) to a
/// tetrahedron. Deterministic. Throws std::invalid_argument when the mesh is not such a surface
/// (the caller validates first). Polls `control`; `progress` (if given) hears the fraction done.
ProgressiveMesh coarsen_to_tetrahedron(const Vertices& V, const Faces& F, const JobControl* control = nullptr,
                                       const std::function<void(double)>& progress = {});

/// The order in which a refinement inserts the vertices: the base four, then the removed
/// vertices from the last collapse to the first.
std::vector<int> insertion_order(const ProgressiveMesh& pm);

}  // namespace meshmark
