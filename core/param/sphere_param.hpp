#pragma once
// A bijective map of a closed genus-0 mesh onto the unit sphere, proven so. By default the
// progressive-mesh map (core/param/progressive_sphere_map: bijective by construction, its area
// spread by a fold-free stretch descent); optionally the conformalized mean curvature flow, with
// projection, Möbius centering and local repair where triangles flipped. Then an area-correcting
// flow, and an exact check of every triangle's orientation and of the total area.
// Deterministic: the same input gives the same map, bit for bit, on the same build, whatever
// the number of threads.

#include <optional>
#include <stdexcept>

#include "core/mesh/mesh.hpp"
#include "core/param/conformal_flow.hpp"
#include "core/param/equalize_area.hpp"
#include "core/param/mobius_center.hpp"
#include "core/param/progressive_sphere_map.hpp"
#include "core/param/repair_spherical_flips.hpp"
#include "core/util/input_error.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

enum class SphereMethod {
  progressive,     ///< the default: coarsen to a tetrahedron, refine vertex by vertex; cannot fold
  conformal_flow,  ///< conformalized mean curvature flow: fails on long protrusions
};
std::string to_string(SphereMethod method);
SphereMethod parse_sphere_method(const std::string& name);  ///< throws std::invalid_argument

struct SphereParamOptions {
  SphereMethod method = SphereMethod::progressive;
  ProgressiveSphereMapOptions progressive;
  ConformalFlowOptions flow;
  MobiusCenterOptions centering;
  RepairOptions repair;
  /// Run the diffusion-cartogram area correction after the map. Default: only after the
  /// conformal flow, whose limbs it must un-shrink; after the progressive map it made the worst
  /// faces worse on 10 of the 18 genus-0 meshes (its coarse density grid cannot resolve limbs the
  /// stretch descent already sized), so it stays off there.
  std::optional<bool> equalize_area;
  EqualizeAreaOptions equalization;
  /// The job stage this runs as, and its share of the job's progress.
  std::string stage = "parameterize";
  double progress_from = 0, progress_to = 1;
};

/// Spread of the ratio (share of sphere area) / (share of surface area) over the faces.
struct AreaDistortion {
  double min = 0, p05 = 0, median = 0, p95 = 0, max = 0;
};

struct SphereParam {
  Vertices S;  ///< #V×3 unit vectors: the image of each vertex
  Faces F;     ///< the faces, wound outward (the input's, flipped if it was inward)
  SphereMethod method = SphereMethod::progressive;
  bool flipped_input = false;        ///< the input wound inward and was flipped
  std::size_t flipped_faces = 0;     ///< after repair: 0, or the map would have been refused
  double degree = 0;                 ///< Σ signed spherical areas / 4π: 1
  ProgressiveSphereMap progressive;  ///< its statistics (S moved out), for the progressive method
  int flow_iterations = 0;           ///< conformal flow only, as the next four
  int factorizations = 0;
  int repair_rounds = 0;
  std::size_t flipped_before_repair = 0;
  AreaDistortion map_area_distortion;  ///< of the map before the area-correcting step
  AreaDistortion area_distortion;      ///< of the final map
  EqualizeAreaResult equalization;
  double map_seconds = 0;  ///< the progressive map or the flow, with its repair
  double equalize_seconds = 0;
  double seconds = 0;  ///< all of it
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
