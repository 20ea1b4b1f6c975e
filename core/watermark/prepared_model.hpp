#pragma once
// Everything about an original mesh that embedding and detection need and that depends only on
// the mesh (the pipeline's steps 1–6): validation, outward faces, normals, the bijective
// spherical map, the grid and the samples on it. Deterministic, so a server computes it once per
// registered model.

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

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
  /// level with at least twice as many grid vertices as mesh vertices, at most 9.
  SamplingOptions sampling = {5, -1, 0.005};
};

/// A mesh that cannot be watermarked; the message lists the validation problems.
class ModelRefused : public InputError {
 public:
  explicit ModelRefused(const MeshReport& report);
  MeshReport report;
};

/// A value computed on first use, once, by whichever thread needs it first.
template <typename T>
struct Lazy {
  std::once_flag once;
  T value;
};

struct PreparedModel {
  Mesh mesh;                    ///< the original, as given (faces in their original winding)
  Faces outward;                ///< the faces wound outward
  MeshReport report;
  std::string digest;           ///< mesh_digest(mesh)
  Vertices normals;             ///< #V×3 outward unit vertex normals
  Eigen::VectorXd vertex_area;  ///< #V lumped areas
  double diagonal = 0;          ///< bounding-box diagonal
  SphereParam param;
  BaseSolid base = BaseSolid::tetrahedron;
  std::shared_ptr<const SphereGrid> grid;
  GridSampling sampling;        ///< level J, the samples and each vertex's cell at level J
  Vertices sample_normals;      ///< V_J×3 unit normals of the surface at the samples
  double prepare_seconds = 0;
  /// Detection's nuisance fields (nuisance_fields.hpp), made on the first detection and shared
  /// by the copies of this model: they depend only on the mesh and its normals.
  std::shared_ptr<Lazy<Eigen::MatrixXd>> nuisance = std::make_shared<Lazy<Eigen::MatrixXd>>();

  int level() const { return sampling.level; }
  int sample_count() const { return grid->vertex_count(sampling.level); }
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
