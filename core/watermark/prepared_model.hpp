#pragma once
// Everything about an original mesh that embedding and detection need and that depends only on
// the mesh: validation, consistently wound faces, normals, and the carrier basis the validation
// chose — the bijective spherical map with the grid and the samples on it (the pipeline's steps
// 1–6; for a genus-0 surface with holes, on the mesh with its holes closed virtually), or bumps
// on the mesh itself. Deterministic, so a server computes it once per registered model.

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "core/basis/multiscale_bumps.hpp"
#include "core/grid/sample_on_grid.hpp"
#include "core/grid/sphere_grid.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "core/param/sphere_param.hpp"
#include "core/util/input_error.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct PrepareOptions {
  BaseSolid base = BaseSolid::tetrahedron;
  SphereParamOptions param;
  /// The paper's level rule; sampling.max_level < 0 picks the cap from the mesh size: the first
  /// level from sampling.start_level with at least grid_samples_per_vertex grid vertices per
  /// mesh vertex, at most max_grid_level.
  SamplingOptions sampling = {5, -1, 0.005};
  double grid_samples_per_vertex = 2;
  int max_grid_level = 9;  ///< tetrahedron level 9: 524,290 samples
  BumpBasisOptions bumps;
  /// Bumps even where the sphere applies: for measuring one basis against the other (eval --basis).
  bool force_bumps = false;
};

/// A mesh that cannot be watermarked; the message lists the validation problems.
class ModelRefused : public InputError {
 public:
  explicit ModelRefused(const MeshReport& report);
  MeshReport report;
};

class CarrierCache;  // carrier_cache.hpp

/// Holds a model's CarrierCache. What the cache keeps refers to the model holding it, so a copy
/// or an assignment of the model starts with an empty cache of its own.
struct CarrierCacheSlot {
  CarrierCacheSlot();
  ~CarrierCacheSlot();
  CarrierCacheSlot(const CarrierCacheSlot&);
  CarrierCacheSlot& operator=(const CarrierCacheSlot&);
  std::unique_ptr<CarrierCache> cache;
};

/// A value computed on first use, once, by whichever thread needs it first.
template <typename T>
struct Lazy {
  std::once_flag once;
  T value;
};

struct PreparedModel {
  Mesh mesh;                            ///< the original, as given (faces in their original winding)
  Faces outward;                        ///< the faces wound outward (per patch, see orient_patches, for bumps)
  MeshBasis basis = MeshBasis::sphere;  ///< what carries the watermark (report.basis, or bumps when filling failed)
  std::string basis_reason;             ///< why, in words
  MeshReport report;
  std::string digest;           ///< mesh_digest(mesh)
  Vertices normals;             ///< #V×3 outward unit vertex normals
  Eigen::VectorXd vertex_area;  ///< #V lumped areas
  double diagonal = 0;          ///< bounding-box diagonal
  // The sphere (basis sphere or sphere_filled):
  Mesh filled;        ///< sphere_filled: the mesh with its holes closed, outward (original rows first)
  SphereParam param;  ///< of `filled` when filled, else of `mesh`
  BaseSolid base = BaseSolid::tetrahedron;
  std::shared_ptr<const SphereGrid> grid;
  GridSampling sampling;  ///< level J, the samples and each vertex's cell at level J
  // Bumps (basis bumps):
  std::shared_ptr<const BumpBasis> bumps;
  BumpBasisOptions bump_options;  ///< what built `bumps` (a stored model rebuilds them with it)
  double prepare_seconds = 0;
  /// Detection's nuisance fields (nuisance_fields.hpp), made on the first detection and shared
  /// by the copies of this model: they depend only on the mesh and its normals.
  std::shared_ptr<Lazy<Eigen::MatrixXd>> nuisance = std::make_shared<Lazy<Eigen::MatrixXd>>();
  /// The spread scheme's carriers and plans (carrier_cache.hpp), built on first use.
  CarrierCacheSlot carriers;

  /// The original with its faces wound outward: what every reading registers on and measures along.
  Mesh outward_mesh() const { return {mesh.V, outward}; }
  bool spherical() const { return basis == MeshBasis::sphere || basis == MeshBasis::sphere_filled; }
  int level() const { return spherical() ? sampling.level : 0; }
  int sample_count() const { return spherical() ? grid->vertex_count(sampling.level) : 0; }
  /// Coefficients a carrier signal has: grid vertices, or bumps.
  long carrier_signal_size() const { return spherical() ? sample_count() : static_cast<long>(bumps->values.cols()); }
};

/// Grids are large and the same for every model of a base and level: share them.
class GridCache {
 public:
  std::shared_ptr<const SphereGrid> get(BaseSolid base, int levels);

 private:
  std::mutex mutex_;
  std::map<std::pair<int, int>, std::weak_ptr<const SphereGrid>> grids_;
};

/// Prepares a model. Throws ModelRefused for a mesh that cannot be watermarked, SphereParamError
/// when the parameterization cannot be made bijective, Canceled or TimeLimitExceeded when
/// `control` says so.
PreparedModel prepare_model(const Mesh& mesh, const PrepareOptions& options = {}, const JobControl* control = nullptr,
                            GridCache* grids = nullptr);

}  // namespace meshmark
