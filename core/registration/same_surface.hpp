#pragma once
// Whether a mesh is another one's surface re-saved with fewer digits, renumbered or moved: a
// master re-exported from a modelling tool is still the original a copy was made from.

#include "core/registration/align_meshes.hpp"

namespace meshmark {

/// Registered rigidly (an original bent into another shape is another original), a surface within
/// this share of the original's diagonal (MRMS) is the original: 6 significant digits leave about
/// 1e-7, the mildest edit a user would call a change (a vertex moved by a tenth of the diagonal
/// on a 1,000-vertex mesh) about 1e-4.
inline constexpr double kSameSurfaceMrms = 1e-5;

struct SurfaceMatch {
  double mrms_relative = 0;  ///< after registration, of the original's diagonal
  bool same = false;         ///< mrms_relative below kSameSurfaceMrms
};

/// `given` registered onto `original` (its pose, scale and vertex order free), then its MRMS from
/// it. Polls `control` (Canceled, TimeLimitExceeded).
SurfaceMatch match_surface(const Mesh& given, const RegistrationTarget& original, const JobControl* control = nullptr);

}  // namespace meshmark
