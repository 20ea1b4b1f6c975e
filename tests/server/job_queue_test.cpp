#include "server/jobs/job_queue.hpp"

#include <gtest/gtest.h>

#include <mutex>
#include <set>
#include <thread>

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

// Three workers: a model's embed job, queued behind its preparation, waits for it although a
// worker is free; another model's job does not.
TEST(JobQueue, AModelsJobsWaitForItsPreparation) {
  GatedRunner gate;
  JobQueue queue(8, 3, gate.runner());
  queue.push_recovered({"prepare", "o", "m1", true});
  queue.push_recovered({"embed", "o", "m1", false});
  queue.push_recovered({"other", "o", "m2", false});
  gate.wait_started(2);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // room for a wrong start
  {
    std::lock_guard lock(gate.mutex);
    EXPECT_EQ(gate.started, (std::set<std::string>{"prepare", "other"}));
  }
  gate.release();
  gate.wait_started(3);
  EXPECT_TRUE(queue.drain(std::chrono::seconds(10)));
  std::lock_guard lock(gate.mutex);
  EXPECT_TRUE(gate.finished.count("prepare"));
}

// An idle worker asks the claim for work elsewhere: what it finds runs; while it finds nothing it
// is asked once per interval, not in a busy loop.
TEST(JobQueue, AnIdleWorkerRunsWhatItClaimsAndAsksOncePerInterval) {
  GatedRunner gate;
  gate.release();
  std::atomic<int> asked{0};
  JobQueue::Options options;
  options.claim_interval = std::chrono::milliseconds(100);
  options.claim = [&]() -> std::optional<QueuedJob> {
    if (++asked == 1) return QueuedJob{"elsewhere", "o", "m", false};
    return std::nullopt;
  };
  JobQueue queue(4, 2, gate.runner(), options);
  gate.wait_started(1);
  std::this_thread::sleep_for(std::chrono::milliseconds(450));
  EXPECT_TRUE(queue.drain(std::chrono::seconds(10)));
  std::lock_guard lock(gate.mutex);
  EXPECT_EQ(gate.finished, (std::set<std::string>{"elsewhere"}));
  EXPECT_GE(asked.load(), 3);
  EXPECT_LE(asked.load(), 8) << "two idle workers share one claim per interval";
}

// A job pushed while a worker is free is started here; one pushed while every worker is taken is
// announced, for idle daemons elsewhere to claim.
TEST(JobQueue, AJobNoWorkerHereCanStartIsAnnounced) {
  GatedRunner gate;
  std::atomic<int> announced{0};
  JobQueue::Options options;
  options.announce = [&] {
    ++announced;
    throw std::runtime_error("the store is away");  // logged, never the pusher's problem
  };
  JobQueue queue(4, 1, gate.runner(), options);
  ASSERT_TRUE(queue.reserve());
  queue.push("a");
  EXPECT_EQ(announced, 0) << "a free worker takes it";
  gate.wait_started(1);
  ASSERT_TRUE(queue.reserve());
  queue.push("b");
  EXPECT_EQ(announced, 1);
  queue.push_recovered({"c", "", "", false});
  EXPECT_EQ(announced, 2);
  gate.release();
  EXPECT_TRUE(queue.drain(std::chrono::seconds(10)));
}

// No worker: places are held until a job is canceled. Owner "a" holds at most half the places;
// "b" still finds room; a place given back or freed by a cancel is "a"'s again.
TEST(JobQueue, AnOwnerHoldsAtMostItsShareOfThePlaces) {
  JobQueue::Options options;
  options.owner_share = 0.5;
  JobQueue queue(
      4, 0, [](const std::string&, const std::atomic<bool>&) {}, options);
  ASSERT_EQ(queue.owner_places(), 2u);
  ASSERT_TRUE(queue.reserve("a"));
  queue.push("a1", "a");
  ASSERT_TRUE(queue.reserve("a"));
  EXPECT_FALSE(queue.reserve("a"));
  EXPECT_EQ(queue.held_by("a"), 2u);
  EXPECT_TRUE(queue.reserve("b"));
  queue.release_reservation("a");
  EXPECT_EQ(queue.held_by("a"), 1u);
  ASSERT_TRUE(queue.reserve("a"));
  queue.push("a2", "a");
  EXPECT_EQ(queue.cancel("a1"), JobQueue::Cancel::dequeued);
  EXPECT_TRUE(queue.reserve("a"));
  EXPECT_TRUE(queue.drain(std::chrono::seconds(1)));
}

// Two workers busy with owner "a"'s jobs, two more of "a" queued before one of "b": when a
// worker frees, "b"'s job runs next, not "a"'s older ones.
TEST(JobQueue, AFreeWorkerTakesAJobOfTheOwnerWithTheFewestRunning) {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::string> order;
  std::set<std::string> released;
  JobQueue queue(8, 2, [&](const std::string& id, const std::atomic<bool>&) {
    std::unique_lock lock(mutex);
    order.push_back(id);
    changed.notify_all();
    changed.wait(lock, [&] { return released.count(id) > 0; });
  });
  const auto started = [&](std::size_t n) {
    std::unique_lock lock(mutex);
    return changed.wait_for(lock, std::chrono::seconds(10), [&] { return order.size() >= n; });
  };
  for (const auto& [id, owner] : {std::pair{"a1", "a"}, {"a2", "a"}}) {
    ASSERT_TRUE(queue.reserve(owner));
    queue.push(id, owner);
  }
  ASSERT_TRUE(started(2));
  for (const auto& [id, owner] : {std::pair{"a3", "a"}, {"a4", "a"}, {"b1", "b"}}) {
    ASSERT_TRUE(queue.reserve(owner));
    queue.push(id, owner);
  }
  {
    std::lock_guard lock(mutex);
    released.insert("a1");
    changed.notify_all();
  }
  ASSERT_TRUE(started(3));
  {
    std::lock_guard lock(mutex);
    EXPECT_EQ(order[2], "b1");
    released.insert({"a2", "a3", "a4", "b1"});
    changed.notify_all();
  }
  EXPECT_TRUE(queue.drain(std::chrono::seconds(10)));
}

}  // namespace
}  // namespace meshmark::server

namespace meshmark::server {
namespace {

TEST(JobQueue, AJobTheStoreRefusedRunsAgainUntilItIsStoredAndIsCountedMeanwhile) {
  std::atomic<int> runs{0};
  std::atomic<bool> store_full{true};
  JobQueue::Options options;
  options.first_retry = std::chrono::milliseconds(20);
  JobQueue queue(
      4, 1,
      [&](const std::string&, const std::atomic<bool>&) {
        ++runs;
        if (store_full) throw RetryLater("the disk is full");
      },
      options);
  ASSERT_TRUE(queue.reserve());
  queue.push("job_1");
  while (runs < 3) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(queue.counts().retrying, 1u);  // owned by the queue, not lost
  store_full = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (queue.counts().retrying > 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(queue.counts().retrying, 0u);
  const int settled = runs;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(runs, settled);  // not run again once stored
}

TEST(JobQueue, CancelingAJobWaitingForStorageRunsItNow) {
  std::atomic<int> runs{0};
  JobQueue::Options options;
  options.first_retry = std::chrono::hours(1);
  JobQueue queue(
      4, 1,
      [&](const std::string&, const std::atomic<bool>&) {
        if (++runs == 1) throw RetryLater("the disk is full");
      },
      options);
  ASSERT_TRUE(queue.reserve());
  queue.push("job_1");
  while (queue.counts().retrying == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(queue.cancel("job_1"), JobQueue::Cancel::retried_now);  // it then finds its cancel in the store
  while (runs < 2) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  while (queue.counts().retrying > 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(runs, 2);
}

}  // namespace
}  // namespace meshmark::server
