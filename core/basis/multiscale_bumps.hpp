#pragma once
// A multiresolution carrier basis on the mesh itself, for meshes the sphere cannot take (handles,
// several parts, non-manifold spots): smooth bumps of graph-geodesic radius at several scales,
// centred on vertices spread evenly over the surface — scalar basis functions built on the
// original, after Praun, Hoppe and Finkelstein (1999). A bump never crosses from one component
// to another; components too small to carry signal get none. Depends only on the mesh.
//
// The finest band's spacing s makes a bump's disk (radius `radius` × s) hold about
// `finest_support_vertices` vertices at the mesh's median vertex density; each coarser band
// doubles the spacing (a quarter as many bumps), while it keeps `min_bumps`, at most `max_bands`
// bands. A bump has value (1 − (d/r)²)² at graph distance d < r. Sizing from the finest band at
// the median density keeps small and unevenly dense meshes (a low-poly asset) markable and gives
// large ones capacity where the surface has it.

#include <Eigen/Sparse>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct BumpBasisOptions {
  double finest_support_vertices =
      16;  ///< vertices a finest-band bump's disk holds at the median density (graph distance reaches ~15 % fewer)
  int min_bumps = 96;  ///< no band with fewer bumps
  int max_bands = 4;
  double radius = 1.75;             ///< bump radius, in units of its band's spacing
  int min_component_vertices = 64;  ///< components with fewer vertices carry nothing
};

struct BumpBasis {
  Eigen::SparseMatrix<double> values;  ///< #V × K: bump k at every vertex
  std::vector<int> band;               ///< per bump, 0 = coarsest
  std::vector<int> center;             ///< per bump: its centre vertex
  std::vector<double> roughness;       ///< per bump: the surface's mean roughness under it (raw)
  std::vector<double> band_support;    ///< per band: mean vertices a bump covers
  std::vector<int> component;          ///< per vertex: its component, −1 if it carries nothing
  std::size_t marked_components = 0, skipped_components = 0, skipped_vertices = 0;
  int bands() const { return static_cast<int>(band_support.size()); }
};

BumpBasis multiscale_bumps(const Mesh& mesh, const BumpBasisOptions& options = {}, const JobControl* control = nullptr);

}  // namespace meshmark
