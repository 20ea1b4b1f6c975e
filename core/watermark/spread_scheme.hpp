#pragma once
// The spread scheme's embedding and detection (see spread_plan.hpp for where bits go).

#include "core/watermark/watermark.hpp"

namespace meshmark {

EmbedResult embed_spread(const PreparedModel& model, const std::string& key, const Bits& payload,
                         const WatermarkOptions& options);

/// `aligned` is the suspect already mapped into the original's frame.
void detect_spread(const PreparedModel& model, const Mesh& aligned, const std::string& key,
                   const DetectOptions& options, DetectResult& result);

}  // namespace meshmark
