#include "server/jobs/job_runner.hpp"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <sstream>
#include <thread>

#include "core/attacks/simplify.hpp"
#include "core/io/write_mesh.hpp"
#include "server/store/sqlite_store.hpp"
#include "tests/process_threads.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/server/store_records.hpp"
#include "tests/test_data.hpp"
#include "server/store/blob_keys.hpp"

namespace meshmark::server {
namespace {

class JobRunnerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    store.insert_owner({"own_1", "o", "t"}, "h");
    ModelRecord model = test::preparing_model("mdl_1", "own_1");
    model.vertices = test::procedural_mesh("creature").V.rows();
    store.insert_model(model, test::job_record("job_1", "own_1", "mdl_1", JobKind::prepare));
  }
  JobRecord run() {
    JobRunner runner({store, blobs, models, memory, metrics, system_clock(), ""}, config, "master key");
    runner.run("job_1", cancel);
    return *store.job_by_id("job_1");
  }
  bool waits_for_memory() {
    for (int i = 0; i < 500; ++i, std::this_thread::sleep_for(std::chrono::milliseconds(10)))
      if (store.job_by_id("job_1")->stage == "waiting for memory") return true;
    return false;
  }
  void store_creature() {
    blobs.put(original_key("mdl_1"),
              write_mesh_to_memory(test::procedural_mesh("creature"), MeshFormat::ply, {.binary = true}));
  }

  std::filesystem::path dir = test::temp_dir("runner");
  SqliteStore store{dir / "db"};
  LocalBlobStore blobs{dir / "blobs"};
  MemoryBudget memory{std::size_t{8} << 30};
  ModelCache models{blobs, 2, memory};
  Metrics metrics;
  DaemonConfig config;
  std::atomic<bool> cancel{false};
};

TEST_F(JobRunnerTest, PreparingMarksTheModelReadyAndStoresThePreparedData) {
  store_creature();
  const JobRecord job = run();
  EXPECT_EQ(job.state, JobState::succeeded) << job.error;
  EXPECT_EQ(job.attempts, 1);
  EXPECT_EQ(store.model_by_id("mdl_1")->state, ModelState::ready);
  EXPECT_TRUE(blobs.get(prepared_key("mdl_1")));
}

TEST_F(JobRunnerTest, AnInternalFailureShowsTheUserAGenericMessageAndLogsTheDetail) {
  std::ostringstream log;
  const auto previous = spdlog::default_logger();
  spdlog::set_default_logger(
      std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log)));
  const JobRecord job = run();  // the model's mesh is not in the blob store: the daemon's fault, not the user's
  spdlog::set_default_logger(previous);
  EXPECT_EQ(job.state, JobState::failed);
  EXPECT_EQ(job.error, "internal error");
  EXPECT_NE(log.str().find("missing from the store"), std::string::npos) << log.str();
  EXPECT_EQ(store.model_by_id("mdl_1")->state, ModelState::failed);
}

TEST_F(JobRunnerTest, AProblemWithTheInputIsShownToTheUser) {
  blobs.put(original_key("mdl_1"), write_mesh_to_memory(test::cube(), MeshFormat::ply, {.binary = true}));
  const JobRecord job = run();
  EXPECT_EQ(job.state, JobState::failed);
  EXPECT_NE(job.error.find("at least 100"), std::string::npos) << job.error;
}

// Seven parts of 21 vertices: valid (140 vertices in parts that may carry), but no band holds
// a 16-bit code. The model is refused when prepared, not after its first embed job.
TEST_F(JobRunnerTest, AModelThatCannotCarryTheShortestAssignedPayloadIsRefused) {
  const Mesh piece = simplify(test::creature(1), 0.5);
  Mesh parts = piece;
  for (int k = 1; k < 7; ++k) parts = test::side_by_side(parts, piece, 3.0 * k);
  blobs.put(original_key("mdl_1"), write_mesh_to_memory(parts, MeshFormat::ply, {.binary = true}));
  const JobRecord job = run();
  EXPECT_EQ(job.state, JobState::failed);
  EXPECT_NE(job.error.find("carries no payload"), std::string::npos) << job.error;
  EXPECT_NE(job.error.find("at least 16"), std::string::npos) << job.error;
  EXPECT_EQ(store.model_by_id("mdl_1")->state, ModelState::failed);
}

TEST_F(JobRunnerTest, AJobPastItsTimeLimitFails) {
  store_creature();
  config.job_time_limit_seconds = 0;
  const JobRecord job = run();
  EXPECT_EQ(job.state, JobState::failed);
  EXPECT_NE(job.error.find("limit"), std::string::npos) << job.error;
}

TEST_F(JobRunnerTest, ACanceledJobEndsCanceled) {
  store_creature();
  cancel = true;
  EXPECT_EQ(run().state, JobState::canceled);
}

TEST_F(JobRunnerTest, AJobRunsOnTheThreadsPerJobItIsGiven) {
  store_creature();
  config.threads_per_job = 1;
  JobRecord job;
  EXPECT_EQ(test::new_threads_while([&] { job = run(); }), 1u) << "the watcher only: the job ran on its worker";
  EXPECT_EQ(job.state, JobState::succeeded) << job.error;
}

TEST_F(JobRunnerTest, AJobOfTwoThreadsPerJobDoesSplitItsLoops) {  // the control of the test above
  // A larger shape: its loops last long enough for the watcher to see them on a loaded machine.
  blobs.put(original_key("mdl_1"),
            write_mesh_to_memory(test::procedural_mesh("creature_large"), MeshFormat::ply, {.binary = true}));
  config.threads_per_job = 2;
  EXPECT_GE(test::new_threads_while([&] { run(); }), 2u);
}

// Runs job_1 on another thread and returns once it waits for memory.
TEST_F(JobRunnerTest, AJobWaitsWhileOthersHoldTheMemoryAndRunsOnceItIsFreed) {
  store_creature();
  auto held = memory.try_reserve(memory.ceiling());
  ASSERT_TRUE(held);
  std::thread worker([&] { run(); });
  ASSERT_TRUE(waits_for_memory()) << "stage: " << store.job_by_id("job_1")->stage;
  EXPECT_EQ(store.job_by_id("job_1")->state, JobState::running);
  held.reset();
  worker.join();
  EXPECT_EQ(store.job_by_id("job_1")->state, JobState::succeeded);
  const auto vertices = static_cast<std::size_t>(store.model_by_id("mdl_1")->vertices);
  EXPECT_EQ(memory.reserved(), kPreparedBytesPerVertex * vertices)
      << "the job's memory is back; the cached model's is held";
}

TEST_F(JobRunnerTest, AKeptModelGivesItsMemoryUpWhenItIsNeeded) {
  store_creature();
  ASSERT_EQ(run().state, JobState::succeeded);
  const auto vertices = static_cast<std::size_t>(store.model_by_id("mdl_1")->vertices);
  ASSERT_EQ(memory.reserved(), kPreparedBytesPerVertex * vertices);
  models.make_room(memory.available());
  EXPECT_EQ(memory.reserved(), kPreparedBytesPerVertex * vertices) << "there was room: nothing is dropped";
  models.make_room(memory.ceiling());
  EXPECT_EQ(memory.reserved(), 0u);
  EXPECT_NE(models.get("mdl_1"), nullptr) << "a dropped model is loaded again from the store";
}

TEST_F(JobRunnerTest, AJobWaitingForMemoryCanBeCanceled) {
  store_creature();
  auto held = memory.try_reserve(memory.ceiling());
  std::thread worker([&] { run(); });
  ASSERT_TRUE(waits_for_memory());
  cancel = true;
  worker.join();
  EXPECT_EQ(store.job_by_id("job_1")->state, JobState::canceled);
}

TEST_F(JobRunnerTest, AFinishedJobIsNotRunAgain) {
  store_creature();
  ASSERT_EQ(run().state, JobState::succeeded);
  EXPECT_EQ(run().attempts, 1);
}

}  // namespace
}  // namespace meshmark::server
