#pragma once
// The spread scheme's embedding and detection (see spread_plan.hpp for where bits go).

#include "core/util/job_control.hpp"
#include "core/watermark/watermark.hpp"

namespace meshmark {

EmbedResult embed_spread(const PreparedModel& model, const std::string& key, const Bits& payload,
                         const WatermarkOptions& options, const JobControl* control = nullptr);

/// Reads the payload from `measured` (the suspect's offset at the original's vertices,
/// read_suspect) in three steps: estimate the carriers, choose a reading, score it. Fills the
/// scheme's part of the result: decoded payload, statistics, p-values, correlation, and the
/// seconds of the estimate and decode stages.
DetectResult detect_spread(const PreparedModel& model, const Displacement& measured, const std::string& key,
                           const DetectOptions& options, const JobControl* control = nullptr);

}  // namespace meshmark
