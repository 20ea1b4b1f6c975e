#pragma once
// Jin et al.'s embedding rule, kept to reproduce their Table 1. The sampled geometry is
// transformed (vector wavelet coefficients, mesh scaled to a unit bounding-box diagonal), and
// each carrier coefficient c moves along its own direction: c' = c + g f(c) w ĉ, with
// f(c) = √|c| / j in detail band j (1 = the coarsest detail band) and f(c) = log(1 + |c|) in the
// approximation, and w = ±1 the carrier's watermark bit. The change is transformed back and
// applied at the vertices; g is set by the distortion budget.
//
// Each carrier holds one payload bit (payload bits are dealt to carriers by the keyed
// generator and hidden by keyed ±1 chips); there is no error-correcting code. A coefficient whose
// hat function the original's vertices hardly see (grid_coverage.hpp) is no carrier: it would
// move no vertex, and the paper, which reads its own resampled mesh, never meets one. Detection reads
// the suspect's displacement along the original's vertex normals (we never parameterize a
// suspect), estimates each carrier's amplitude along its known direction ĉ through the same
// synthesis-and-interpolation model the embedding used, and reads the carrier's bit as the sign;
// a payload bit is the majority (soft sum) of its carriers.

#include "core/util/job_control.hpp"
#include "core/watermark/watermark.hpp"

namespace meshmark {

EmbedResult embed_paper(const PreparedModel& model, const std::string& key, const Bits& payload,
                        const WatermarkOptions& options, const JobControl* control = nullptr);

/// Reads the payload from `measured` (read_suspect): estimate, choose the best-scoring vote,
/// score it. Fills the scheme's part of the result, as detect_spread does.
DetectResult detect_paper(const PreparedModel& model, const Displacement& measured, const std::string& key,
                          const DetectOptions& options, const JobControl* control = nullptr);

}  // namespace meshmark
