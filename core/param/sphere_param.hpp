#pragma once
// A bijective map of a closed genus-0 mesh onto the unit sphere, proven so: conformalized mean
// curvature flow, projection, Möbius centering, local repair where triangles flipped, an
// area-correcting flow, and an exact check of every triangle's orientation and of the total area. Deterministic: the same input
// gives the same map, bit for bit, on the same build.

#include <stdexcept>

#include "core/mesh/mesh.hpp"
#include "core/param/conformal_flow.hpp"
#include "core/param/equalize_area.hpp"
#include "core/param/mobius_center.hpp"
#include "core/param/repair_spherical_flips.hpp"
#include "core/util/input_error.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct SphereParamOptions {
  ConformalFlowOptions flow;
  MobiusCenterOptions centering;
  RepairOptions repair;
  bool equalize_area = true;  ///< run the area-correcting step after the conformal map
  EqualizeAreaOptions equalization;
};

/// Spread of the ratio (share of sphere area) / (share of surface area) over the faces.
struct AreaDistortion {
  double min = 0, p05 = 0, median = 0, p95 = 0, max = 0;
};

struct SphereParam {
  Vertices S;                      ///< #V×3 unit vectors: the image of each vertex
  Faces F;                         ///< the faces, wound outward (the input's, flipped if it was inward)
  bool flipped_input = false;      ///< the input wound inward and was flipped
  std::size_t flipped_faces = 0;   ///< after repair: 0, or the map would have been refused
  double degree = 0;               ///< Σ signed spherical areas / 4π: 1
  int flow_iterations = 0;
  int factorizations = 0;
  int repair_rounds = 0;
  std::size_t flipped_before_repair = 0;
  AreaDistortion conformal_area_distortion;  ///< of the conformal map, before area correction
  AreaDistortion area_distortion;            ///< of the final map
  EqualizeAreaResult equalization;
  double flow_seconds = 0;
  double equalize_seconds = 0;
  double seconds = 0;                        ///< all of it
};

/// The parameterization could not be made bijective; the message says why.
class SphereParamError : public InputError {
 public:
  using InputError::InputError;
};

/// Maps a valid mesh (closed, manifold, genus 0, consistently oriented) to the sphere.
/// Throws SphereParamError when the map cannot be made bijective.
/// Polls `control` throughout (Canceled, TimeLimitExceeded).
SphereParam sphere_param(const Mesh& mesh, const SphereParamOptions& options = {}, const JobControl* control = nullptr);

/// The spread of area ratios of a spherical map against its surface.
AreaDistortion area_distortion(const Vertices& V, const Vertices& S, const Faces& F);

}  // namespace meshmark
