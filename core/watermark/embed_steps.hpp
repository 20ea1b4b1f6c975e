#pragma once
// The embedding both schemes run: plan the carriers, synthesize the change, apply it at the
// strength, then describe the copy. Each of the first three is a stage of the JobControl's
// progress and a key of EmbedResult::seconds (detect_stages.hpp names them); a scheme supplies
// the steps, run_embed_steps runs and times them.

#include "core/util/job_control.hpp"
#include "core/watermark/watermark.hpp"

namespace meshmark {

/// What one embedding works from (the API's request is proto/api.hpp's EmbedRequest); the
/// references must outlive the steps.
struct EmbedInputs {
  const PreparedModel& model;
  const std::string& key;
  const Bits& payload;
  const WatermarkOptions& options;
  int threads = 0;  ///< of the parallel steps; 0: the hardware's
};

class EmbedSteps {
 public:
  virtual ~EmbedSteps() = default;
  /// Carriers, chips and amplitudes for the payload (stage embed_stage::plan).
  virtual void plan() = 0;
  /// The change synthesized and mapped to the vertices (embed_stage::synthesis).
  virtual void synthesize() = 0;
  /// result.mesh: the original with its vertices moved, scaled to the budget (embed_stage::apply).
  virtual void apply(EmbedResult& result) = 0;
  /// The copy's figures and warnings (carriers, displacement); not timed.
  virtual void describe(EmbedResult& result) const = 0;
};

/// Runs `steps` in order under `control` (progress 0, 0.4, 0.8 at the stages; Canceled or
/// TimeLimitExceeded between them), each stage's wall time in result.seconds.
EmbedResult run_embed_steps(EmbedSteps& steps, const JobControl* control);

}  // namespace meshmark
