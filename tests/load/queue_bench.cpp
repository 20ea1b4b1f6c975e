// The job queue's claim path, measured (not a test): N queued no-op jobs claimed by W workers,
// each claim a Store::claim_queued_job, each job then started and ended as a worker would. Prints
// claims per second, claim latency (p50, p99, max) and whether any job ran twice.
// Usage: meshmark_queue_bench STORE [JOBS] [WORKERS]
//   STORE  sqlite:PATH or postgresql://… (a database of its own: the bench fills it)

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "server/store/job_transitions.hpp"
#include "server/store/open_storage.hpp"
#include "server/store/postgres_store.hpp"
#include "server/store/sqlite_store.hpp"

namespace {

using namespace meshmark;
using namespace meshmark::server;
using Steady = std::chrono::steady_clock;

std::unique_ptr<Store> open(const std::string& location, std::size_t workers) {
  if (location.rfind("sqlite:", 0) == 0) return std::make_unique<SqliteStore>(location.substr(7));
  return std::make_unique<PostgresStore>(location, system_clock(), workers);  // a connection per worker
}

void fill(Store& store, int jobs) {
  store.insert_owner({"own_bench", "bench", "t"}, "bench-key-hash");
  ModelRecord model;
  model.id = "mdl_bench";
  model.owner_id = "own_bench";
  model.state = ModelState::ready;
  model.report = nlohmann::json::object();
  JobRecord prepare;
  prepare.id = "job_prepare";
  prepare.owner_id = "own_bench";
  prepare.model_id = model.id;
  prepare.state = JobState::succeeded;
  store.insert_model(model, prepare);
  for (int k = 0; k < jobs; ++k) {
    JobRecord j;
    j.id = "job_" + std::to_string(k);
    j.owner_id = "own_bench";
    j.model_id = model.id;
    j.spec = DetectJobSpec{parse_detect_query("", "", ""), 0};
    j.created_at = std::to_string(1000000 + k);
    j.lease_owner = "mmd_accepting";
    store.insert_job(j);
  }
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: meshmark_queue_bench STORE [JOBS] [WORKERS]\n");
    return 2;
  }
  const int jobs = argc > 2 ? std::stoi(argv[2]) : 10000;
  const int workers = argc > 3 ? std::stoi(argv[3]) : 32;
  const auto store = open(argv[1], static_cast<std::size_t>(workers));
  fill(*store, jobs);
  std::mutex mutex;
  std::vector<double> latencies;
  std::map<std::string, int> runs;
  std::atomic<int> lost_starts{0};
  const auto start = Steady::now();
  std::vector<std::thread> threads;
  for (int w = 0; w < workers; ++w)
    threads.emplace_back([&, w] {
      const std::string me = "mmd_worker" + std::to_string(w);
      while (true) {
        const auto before = Steady::now();
        auto job = store->claim_queued_job(me, "9999");
        const double ms = std::chrono::duration<double, std::milli>(Steady::now() - before).count();
        if (!job) return;
        start_job(*job, "t");
        if (store->start_job(*job) != JobWrite::written) {
          ++lost_starts;
          continue;
        }
        succeed_job(*job, nlohmann::json::object(), "t");
        store->finish_job(*job);
        std::lock_guard lock(mutex);
        latencies.push_back(ms);
        ++runs[job->id];
      }
    });
  for (auto& t : threads) t.join();
  const double seconds = std::chrono::duration<double>(Steady::now() - start).count();
  int twice = 0;
  for (const auto& [id, n] : runs) twice += n > 1;
  const auto counts = store->job_counts();
  const auto succeeded = counts.count({"detect", "succeeded"}) ? counts.at({"detect", "succeeded"}) : 0;
  std::printf(
      "store %s: %d jobs, %d workers: %.0f claims/s (%.2f s), claim latency p50 %.2f ms, p99 %.2f ms, "
      "max %.2f ms; jobs run: %zu, run twice: %d, starts lost to another claim: %d, succeeded in the "
      "store: %lld\n",
      describe_location(argv[1]).c_str(), jobs, workers, static_cast<double>(latencies.size()) / seconds, seconds,
      percentile(latencies, 0.5), percentile(latencies, 0.99), percentile(latencies, 1.0), runs.size(), twice,
      lost_starts.load(), succeeded);
  return twice == 0 && static_cast<int>(runs.size()) == jobs && succeeded == jobs ? 0 : 1;
}
