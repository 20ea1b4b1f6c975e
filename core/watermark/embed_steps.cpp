#include "core/watermark/embed_steps.hpp"

#include "core/watermark/detect_stages.hpp"

namespace meshmark {

EmbedResult run_embed_steps(EmbedSteps& steps, const JobControl* control) {
  EmbedResult result;
  StageTimer stages(result.seconds, control);
  stages.start(embed_stage::plan, 0.0);
  steps.plan();
  stages.start(embed_stage::synthesis, 0.4);
  steps.synthesize();
  stages.start(embed_stage::apply, 0.8);
  steps.apply(result);
  stages.finish();
  steps.describe(result);
  return result;
}

}  // namespace meshmark
