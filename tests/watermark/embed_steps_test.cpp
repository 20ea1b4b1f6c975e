// The embedding skeleton both schemes share, on steps that only record what ran.

#include "core/watermark/embed_steps.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "core/watermark/detect_stages.hpp"

namespace meshmark {
namespace {

class RecordingSteps final : public EmbedSteps {
 public:
  explicit RecordingSteps(std::vector<std::string>& log) : log_(log) {}
  void plan() override { log_.push_back("plan"); }
  void synthesize() override { log_.push_back("synthesize"); }
  void apply(EmbedResult& result) override {
    log_.push_back("apply");
    result.mesh.V = Vertices::Ones(1, 3);
  }
  void describe(EmbedResult& result) const override {
    log_.push_back("describe");
    result.carriers = 7;
  }

 private:
  std::vector<std::string>& log_;
};

TEST(EmbedSteps, RunsPlanSynthesisApplyThenDescribeInOrder) {
  std::vector<std::string> log;
  RecordingSteps steps(log);
  const EmbedResult result = run_embed_steps(steps, nullptr);
  EXPECT_EQ(log, (std::vector<std::string>{"plan", "synthesize", "apply", "describe"}));
  EXPECT_EQ(result.mesh.V.rows(), 1);
  EXPECT_EQ(result.carriers, 7);
}

TEST(EmbedSteps, TimesEachStageUnderItsName) {
  std::vector<std::string> log;
  RecordingSteps steps(log);
  const EmbedResult result = run_embed_steps(steps, nullptr);
  ASSERT_EQ(result.seconds.size(), 3u);
  for (const char* stage : {embed_stage::plan, embed_stage::synthesis, embed_stage::apply})
    EXPECT_GE(result.seconds.at(stage), 0.0) << stage;
}

TEST(EmbedSteps, ReportsEachStageWithGrowingProgress) {
  std::vector<std::pair<std::string, double>> reports;
  JobControl control;
  control.report = [&](const std::string& stage, double progress) { reports.emplace_back(stage, progress); };
  std::vector<std::string> log;
  RecordingSteps steps(log);
  run_embed_steps(steps, &control);
  EXPECT_EQ(reports, (std::vector<std::pair<std::string, double>>{
                         {embed_stage::plan, 0.0}, {embed_stage::synthesis, 0.4}, {embed_stage::apply, 0.8}}));
}

TEST(EmbedSteps, ACancelDuringAStageStopsBeforeTheNext) {
  std::atomic<bool> cancel{false};
  JobControl control;
  control.cancel = &cancel;
  std::vector<std::string> log;
  class CancelingSteps final : public EmbedSteps {
   public:
    CancelingSteps(std::vector<std::string>& log, std::atomic<bool>& cancel) : log_(log), cancel_(cancel) {}
    void plan() override {
      log_.push_back("plan");
      cancel_ = true;
    }
    void synthesize() override { log_.push_back("synthesize"); }
    void apply(EmbedResult&) override { log_.push_back("apply"); }
    void describe(EmbedResult&) const override { log_.push_back("describe"); }

   private:
    std::vector<std::string>& log_;
    std::atomic<bool>& cancel_;
  } steps(log, cancel);
  EXPECT_THROW(run_embed_steps(steps, &control), Canceled);
  EXPECT_EQ(log, std::vector<std::string>{"plan"});
}

}  // namespace
}  // namespace meshmark
