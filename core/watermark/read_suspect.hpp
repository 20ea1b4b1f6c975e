#pragma once
// The first step of detection for every scheme: the aligned suspect's offset from the original
// at each original vertex (read by projection, or at the vertices themselves when they are the
// original's), with outliers clipped and the fields no watermark carries (small
// rigid motion, scale, smoothing shrinkage) removed.

#include "core/registration/align_meshes.hpp"
#include "core/watermark/measure_by_projection.hpp"
#include "core/watermark/prepared_model.hpp"
#include "core/watermark/vertex_offsets.hpp"

namespace meshmark {

/// `target` holds the original's spatial index (the original must be `model.mesh`). Runs on
/// `threads` threads (0: the hardware's).
Displacement read_suspect(const PreparedModel& model, const RegistrationTarget& target, const Mesh& aligned,
                          const DisplacementOptions& options, int threads);

/// The same reading where the suspect's vertices are the original's (vertex_offsets.hpp): each
/// offset's normal part at its own vertex, no surface sampled; vertices without a partner are
/// missing. Outliers clipped and the fields removed as above.
Displacement read_at_vertices(const PreparedModel& model, const VertexOffsets& offsets,
                              const DisplacementOptions& options, int threads);

}  // namespace meshmark
