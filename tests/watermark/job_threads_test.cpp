// The threads a computation uses are its caller's: a JobControl's count reaches every parallel
// loop of preparation, embedding and detection (there is no process-wide setting to fall back on).

#include <gtest/gtest.h>

#include "core/watermark/watermark.hpp"
#include "tests/process_threads.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// Prepare, embed and detect on a 10,242-vertex sphere: large enough that every vertex loop
// would split across threads.
void run_pipeline(const JobControl& control) {
  const PreparedModel model = prepare_model(test::icosphere(5), {}, &control);
  const EmbedResult marked = embed_watermark(model, "k", bits_from_hex("0123456789abcdef"), {}, &control);
  const DetectResult found = detect_watermark(model, marked.mesh, "k", {}, nullptr, &control);
  ASSERT_TRUE(found.detected);
}

TEST(JobThreads, OneThreadRunsTheWholePipelineOnTheCallersThread) {
  JobControl one;
  one.threads = 1;
  EXPECT_EQ(test::new_threads_while([&] { run_pipeline(one); }), 1u) << "the watcher only: all on the caller's";
}

TEST(JobThreads, TwoThreadsDoSplitTheLoops) {  // the control: the watcher does see a loop's threads
  JobControl two;
  two.threads = 2;
  EXPECT_GE(test::new_threads_while([&] { run_pipeline(two); }), 2u);
}

}  // namespace
}  // namespace meshmark
