#pragma once
// The regular spherical grid of Schröder and Sweldens: a base solid (tetrahedron, octahedron or
// icosahedron) projected on the unit sphere and split 1-to-4 recursively, each new vertex the
// normalized midpoint of its edge.
//
// Numbering is nested: the vertices of level j are the prefix [0, V_j) with
// V_j = 2 + (V_0 − 2)·4^j, so a signal on the finest level holds every coarser level. The four
// children of face f of level j are faces 4f .. 4f+3 of level j+1: (a, m_ab, m_ca),
// (m_ab, b, m_bc), (m_ca, m_bc, c), (m_ab, m_bc, m_ca).

#include <array>
#include <string>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

enum class BaseSolid { tetrahedron, octahedron, icosahedron };
/// Every base solid, in the order of the enum.
inline constexpr BaseSolid kBaseSolids[] = {BaseSolid::tetrahedron, BaseSolid::octahedron, BaseSolid::icosahedron};
std::string to_string(BaseSolid base);
/// "tetra"/"tetrahedron", "octa"/"octahedron", "icosa"/"icosahedron"; throws std::invalid_argument.
BaseSolid parse_base_solid(const std::string& name);

/// The neighbours a vertex born at level j+1 (on an edge of level j) needs for prediction:
/// the edge's ends v1, v2; the opposite vertices f1 (of the face where the edge runs v1→v2) and
/// f2; and the butterfly's far vertices e1..e4 (across the edges v1–f1, f1–v2, v1–f2 and f2–v2).
struct Stencil {
  int v1, v2, f1, f2;
  std::array<int, 4> e;
};

struct SphereGrid {
  BaseSolid base = BaseSolid::tetrahedron;
  int levels = 0;                  ///< finest level J
  Vertices points;                 ///< V_J×3 unit vectors
  std::vector<int> vertex_counts;  ///< V_j for j = 0..J
  std::vector<Stencil> stencils;   ///< for vertex m ≥ V_0, at m − V_0
  std::vector<Faces> faces;        ///< faces[j]: F_0·4^j × 3, outward

  int vertex_count(int level) const { return vertex_counts[static_cast<std::size_t>(level)]; }
  const Stencil& stencil(int vertex) const { return stencils[static_cast<std::size_t>(vertex - vertex_counts[0])]; }
  /// The level at which a vertex first appears.
  int level_of(int vertex) const;
};

/// Builds the grid down to `levels` (0 = the base solid). Throws std::invalid_argument for a
/// level below 0 or above 12.
SphereGrid make_sphere_grid(BaseSolid base, int levels);

/// Number of vertices at a level, without building the grid.
long long sphere_grid_vertex_count(BaseSolid base, int level);

/// A point of the sphere located in the grid: the face of a level and the weights of its corners
/// (gnomonic barycentric coordinates: the ray through the point meets the flat triangle there).
struct GridLocation {
  int face = 0;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
};

/// Locates p (|p| = 1) at `level` by descending the nested faces from the base solid.
GridLocation locate_in_grid(const SphereGrid& grid, const Eigen::Vector3d& p, int level);

/// The descent of locate_in_grid from `face` of `from_level` down to `level` (from_level < 0: from
/// the base solid): a caller that already descended to a coarser level goes on from there, to the
/// face the whole descent gives.
int descend_grid(const SphereGrid& grid, const Eigen::Vector3d& p, int from_level, int face, int level);

/// p in `face` of `level`, with its gnomonic barycentric coordinates there.
GridLocation grid_location(const SphereGrid& grid, const Eigen::Vector3d& p, int level, int face);

/// Weights of a, b, c for p in the spherical triangle (a, b, c): det(p,b,c) : det(a,p,c) : det(a,b,p),
/// clamped at 0 and summing to 1.
Eigen::Vector3d gnomonic_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c);

}  // namespace meshmark
