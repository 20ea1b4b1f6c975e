#include "server/jobs/job_queue.hpp"

#include <gtest/gtest.h>

#include <mutex>
#include <set>

namespace meshmark::server {
namespace {

// A runner that blocks each job until released, recording what ran.
struct GatedRunner {
  std::mutex mutex;
  std::condition_variable changed;
  std::set<std::string> started, finished;
  bool open = false;

  JobQueue::Runner runner() {
    return [this](const std::string& id, const std::atomic<bool>& cancel) {
      std::unique_lock lock(mutex);
      started.insert(id);
      changed.notify_all();
      // The cancel flag is an atomic nobody notifies on: poll it, as a real stage would.
      while (!changed.wait_for(lock, std::chrono::milliseconds(5), [&] { return open || cancel.load(); })) {
      }
      finished.insert(id);
    };
  }
  void wait_started(std::size_t n) {
    std::unique_lock lock(mutex);
    changed.wait(lock, [&] { return started.size() >= n; });
  }
  void release() {
    std::lock_guard lock(mutex);
    open = true;
    changed.notify_all();
  }
};

TEST(JobQueue, RefusesBeyondItsCapacityAndAcceptsAgainWhenAPlaceFrees) {
  GatedRunner gate;
  JobQueue queue(2, 1, gate.runner());
  ASSERT_TRUE(queue.reserve());
  queue.push("a");
  gate.wait_started(1);  // "a" runs: the queue is empty again
  ASSERT_TRUE(queue.reserve());
  queue.push("b");
  ASSERT_TRUE(queue.reserve());  // reserved, not yet pushed: it counts
  EXPECT_FALSE(queue.reserve());
  queue.release_reservation();
  EXPECT_TRUE(queue.reserve());
  queue.push("c");
  EXPECT_EQ(queue.depth(), 2u);
  EXPECT_EQ(queue.cancel("b"), JobQueue::Cancel::dequeued);
  EXPECT_EQ(queue.depth(), 1u);
  gate.release();
  EXPECT_TRUE(queue.drain(std::chrono::seconds(10)));
}

TEST(JobQueue, CancelSignalsARunningJob) {
  GatedRunner gate;
  JobQueue queue(4, 1, gate.runner());
  queue.reserve();
  queue.push("a");
  gate.wait_started(1);
  EXPECT_EQ(queue.cancel("a"), JobQueue::Cancel::signaled);
  EXPECT_TRUE(queue.drain(std::chrono::seconds(10)));  // the runner saw the flag and returned
  EXPECT_EQ(queue.cancel("zzz"), JobQueue::Cancel::unknown);
}

TEST(JobQueue, DrainLeavesQueuedJobsAloneAndRefusesNewOnes) {
  GatedRunner gate;
  JobQueue queue(4, 1, gate.runner());
  queue.reserve();
  queue.push("a");
  gate.wait_started(1);
  queue.reserve();
  queue.push("b");
  EXPECT_FALSE(queue.drain(std::chrono::seconds(0)));  // "a" still runs
  EXPECT_FALSE(queue.reserve());
  gate.release();
  EXPECT_TRUE(queue.drain(std::chrono::seconds(10)));
  std::lock_guard lock(gate.mutex);
  EXPECT_EQ(gate.started, (std::set<std::string>{"a"}));  // "b" waits for the next start
}

TEST(JobQueue, RunsJobsOnSeveralWorkersAtOnce) {
  GatedRunner gate;
  JobQueue queue(8, 3, gate.runner());
  for (const char* id : {"a", "b", "c"}) {
    queue.reserve();
    queue.push(id);
  }
  gate.wait_started(3);
  EXPECT_EQ(queue.running(), 3u);
  gate.release();
  EXPECT_TRUE(queue.drain(std::chrono::seconds(10)));
}

}  // namespace
}  // namespace meshmark::server
