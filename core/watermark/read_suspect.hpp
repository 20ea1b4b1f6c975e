#pragma once
// The first step of detection for every scheme: the aligned suspect's offset from the original
// at each original vertex (read by projection), with outliers clipped and the fields no watermark carries (small
// rigid motion, scale, smoothing shrinkage) removed.

#include "core/registration/align_meshes.hpp"
#include "core/watermark/measure_by_projection.hpp"
#include "core/watermark/prepared_model.hpp"

namespace meshmark {

/// `target` holds the original's spatial index (the original must be `model.mesh`). Runs on
/// `threads` threads (0: the hardware's).
Displacement read_suspect(const PreparedModel& model, const RegistrationTarget& target, const Mesh& aligned,
                          const DisplacementOptions& options, int threads);

}  // namespace meshmark
