#pragma once
// Automatic registration of a suspect mesh to the original, for non-blind detection: a
// similarity (rotation, uniform scale, translation) found without a human's initial guess.
//
// A copy that kept the original's vertices in their order (the file as handed out, however moved)
// registers by them at once. Otherwise, when it kept enough of the original's vertices, the pose
// they imply (match_vertices.hpp), refined, is the one candidate. Otherwise, starts: the identity and the 24 rotations
// that map the suspect's principal axes (area-weighted PCA) onto the original's with every sign and order,
// and the poses local shape descriptors vote for (match_features.hpp: a cut copy's axes moved); the
// best-ranked, and those, are refined briefly, and every distinct pose that fits about as well as the best
// is a candidate (a symmetric shape fits as well turned: the watermark, read at each, tells the
// original's turn).
// Then trimmed point-to-plane ICP with uniform scale: only the best-matching fraction of the
// correspondences counts, so noise, crops and pieces do not pull the fit.

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/mesh/similarity.hpp"
#include "core/registration/match_features.hpp"
#include "core/registration/match_vertices.hpp"
#include "core/registration/smooth_deformation.hpp"
#include "core/spatial/aabb_tree.hpp"
#include "core/spatial/point_index.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct AlignOptions {
  double trim = 0.85;             ///< fraction of correspondences kept (the closest)
  int max_points = 20000;         ///< suspect surface samples for the final fit
  int score_points = 500;         ///< samples for ranking the 25 starts without iterating
  int probed_starts = 8;          ///< best-ranked starts refined briefly
  int probed_turned_starts = 25;  ///< ... when the axes leave turns to search
  int probe_points = 1500;
  int probe_iterations = 8;
  int max_iterations = 200;   ///< the full fit's steps on probe_points...
  int dense_iterations = 10;  ///< ... then on max_points
  double tolerance = 1e-8;    ///< stop when a step moves points less than this × the diagonal
  int polish_points = 5000;   ///< then exact closest points on the original's triangles...
  int polish_iterations = 4;  ///< ... for a few steps
  /// Another distinct pose is kept as a candidate when its brief fit is within this factor of the
  /// best start's (shapes with symmetries fit about as well turned).
  double candidate_margin = 2.0;
  /// Distinct probed fits refined fully, the best kMaxAlignmentCandidates of them kept: a brief
  /// probe ranks the right turn of a near-symmetric shape among many about as close.
  int refined_fits = 6;
  bool try_order = true;     ///< a copy that kept the original's vertex order registers by it
  bool try_vertices = true;  ///< the vertices a copy kept first (match_vertices.hpp)
  bool try_features = true;  ///< starts from local shape too (match_features.hpp)
  /// Starts at the scale of the vertex spacing, at either end: a cut copy that kept its vertices
  /// where they match any of many alike (a blade's regular tessellation)
  bool try_spacing = true;
  FeatureOptions features;
  /// Every start probed again, and each turned about every principal axis, when the best
  /// shape-registered fit, unbent or rigid, is poor or leaves part of the suspect off the original.
  bool retry_poor = true;
  /// The suspect's mirror image is registered too unless its own vertices named its pose, and its
  /// poses become candidates where they fit about as well or better (align_candidates).
  bool try_mirror = true;
  /// A best fit registered by shape whose scale the surface leaves open (refitted 3 % larger or
  /// smaller, it fits about as well: a tapered blade cut, shrunk about its tip) is also tried at
  /// every 1 % between, and the mark tells (align_candidates).
  bool sweep_open_scale = true;
  bool turn_about_every_axis = false;  ///< the retry's starts: each axis-ordered start turned by 30° steps
  DeformationOptions deformation;      ///< the non-rigid fit after the rigid one
  bool non_rigid = true;               ///< false: the rigid pose only
};

struct Alignment {
  Similarity transform;  ///< suspect coordinates → original coordinates
  /// Then this smooth field (the identity unless the copy was bent and the field fits it).
  SmoothDeformation deformation;
  double rms = 0;        ///< RMS of the kept distances, relative to the original's bbox diagonal
  double rigid_rms = 0;  ///< ... after the rigid pose alone
  /// Share of the suspect's surface within kOverlapDistance of the original once aligned: below 1
  /// where the suspect holds what the original does not (other parts, or a wrong pose).
  double overlap = 0;
  bool collapsed = false;  ///< the fit changed the scale of its start over kMaxScaleChange times
  int iterations = 0;
  std::string start;  ///< "order", "vertices", "identity" or "pca N"
  /// The suspect is the original's mirror image (a tool's mirror, an engine of the other
  /// handedness): `transform` reflects it (det R = −1), and its start was found on its reflection.
  bool mirrored = false;
  /// Registered by the vertex order (align_by_order): suspect vertex i is original vertex i.
  bool by_order() const { return start == "order"; }
  /// A fit no reading should be trusted on without a look: far from the surface, or half off it.
  bool poor() const;
  /// Suspect coordinates (rows) mapped onto the original: the pose, then the field.
  Vertices apply_to_rows(const Vertices& V) const { return deformation.apply_to_rows(transform.apply_to_rows(V)); }
};

/// What registration needs of the original, computed once per model: dense surface samples
/// with normals in a k-d tree (correspondences need not be exact closest points, only close).
/// How densely the original is sampled for registration: dense enough that the nearest sample's
/// plane is close to the surface.
struct RegistrationSampling {
  double samples_per_vertex = 4;
  Eigen::Index min_samples = 50'000;
  Eigen::Index max_samples = 400'000;
};

struct RegistrationTarget {
  /// `original` with its faces wound outward: their normals are the direction every reading
  /// measures along, so they must be the ones the mark was embedded along.
  explicit RegistrationTarget(Mesh original, const RegistrationSampling& sampling = {});
  RegistrationTarget(const RegistrationTarget&) = delete;  // the tree refers to `mesh`
  RegistrationTarget& operator=(const RegistrationTarget&) = delete;
  const Mesh mesh;
  AabbTree tree;  ///< exact closest points, for the final polish
  Vertices face_normals;
  Vertices samples;         ///< points on the original, uniform by area
  Vertices sample_normals;  ///< the normal of each sample's face
  std::unique_ptr<PointIndex> index;
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;       ///< principal axes (columns), by decreasing variance
  Eigen::Vector3d variances;  ///< along `axes`
  double spread = 0;          ///< sqrt of the total variance
  double diagonal = 0;
  /// The original's vertex signatures (match_vertices.hpp), built on first use.
  const VertexSignatures& vertex_signatures(int threads) const;
  /// The original's local shape descriptors (match_features.hpp), built on first use with the
  /// first caller's options (a target serves one set of options).
  const ShapeFeatures& shape_features(const FeatureOptions& options, int threads) const;

 private:
  mutable std::once_flag signed_, described_;
  mutable std::unique_ptr<VertexSignatures> signatures_;
  mutable std::unique_ptr<ShapeFeatures> features_;
};

/// Whether the original's principal axes leave turns to search (two or three principal variances
/// alike: a bottle, a wheel, a ball). Such a shape registers by its details, and whether a turned
/// copy finds its pose can then depend on the mark itself, not on the shape alone.
bool turns_ambiguous(const RegistrationTarget& target);

/// An alignment is poor when its RMS exceeds this share of the diagonal (noise of 0.3 % leaves
/// about 0.1 %; a wrong pose leaves 1 % and more) or less than kPoorOverlap of it overlaps.
inline constexpr double kPoorAlignmentRms = 0.003;
inline constexpr double kPoorOverlap = 0.8;
inline constexpr double kOverlapDistance = 0.01;  ///< of the diagonal
/// A fit that leaves more than this share of the suspect off the original, however close the
/// rest, is searched again (a copy only cut, simplified or noisy overlaps whole at its pose; a
/// round tower turned about its axis fits its body, and leaves its rock base a tenth off).
inline constexpr double kWholeOverlap = 0.97;
/// A fit that scales the suspect more than this many times up or down from its start collapsed.
inline constexpr double kMaxScaleChange = 4.0;

/// A suspect with the original's vertex count registers by their order (its vertices onto the
/// original's) when at least this share of them land within VertexMatchOptions::tolerance.
inline constexpr double kOrderKeptShare = 0.95;

/// At most this many rigid candidates come from align_candidates, each perhaps beside its
/// unbent twin: detection charges its p-value for as many as it reads.
inline constexpr int kMaxAlignmentCandidates = 6;

/// Registrations of `suspect` (any triangle soup: open, in pieces, any genus) onto the original:
/// the best fit first, then every other distinct pose whose start fitted almost as well (see
/// AlignOptions::candidate_margin), at most kMaxAlignmentCandidates rigid ones; a pose a smooth
/// field fits much better is there twice, with the field and without. Polls `control`
/// throughout (Canceled, TimeLimitExceeded).
std::vector<Alignment> align_candidates(const Mesh& suspect, const RegistrationTarget& target,
                                        const AlignOptions& options = {}, const JobControl* control = nullptr);

/// The suspect as its registration saw it: reflected through the plane x = 0 (its faces rewound)
/// when `a` is mirrored, else as it is. A proper similarity fits its vertices onto the original's,
/// and its faces face as the original's do once `a` places it.
Mesh as_registered(const Mesh& suspect, const Alignment& a);

/// The best of align_candidates.
Alignment align_to_original(const Mesh& suspect, const RegistrationTarget& target, const AlignOptions& options = {},
                            const JobControl* control = nullptr);

}  // namespace meshmark
