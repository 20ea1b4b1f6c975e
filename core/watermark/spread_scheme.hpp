#pragma once
// The spread scheme's embedding and detection (see spread_plan.hpp for where bits go).

#include "core/util/job_control.hpp"
#include "core/watermark/watermark.hpp"

namespace meshmark {

EmbedResult embed_spread(const PreparedModel& model, const std::string& key, const Bits& payload,
                         const WatermarkOptions& options, const JobControl* control = nullptr);

/// `measured`: the suspect's displacement along the original's vertex normals (read_suspect).
void detect_spread(const PreparedModel& model, const Displacement& measured, const std::string& key,
                   const DetectOptions& options, DetectResult& result);

}  // namespace meshmark
