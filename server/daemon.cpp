#include "server/daemon.hpp"

#include <signal.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <thread>
#include <vector>

#include "core/util/atomic_file.hpp"
#include "server/clock.hpp"
#include "server/daemon_secrets.hpp"
#include "server/data_dir_lock.hpp"
#include "server/http/api.hpp"
#include "server/http/http_server.hpp"
#include "server/jobs/job_queue.hpp"
#include "server/jobs/job_runner.hpp"
#include "server/jobs/lease_keeper.hpp"
#include "server/jobs/recover_jobs.hpp"
#include "server/memory_budget.hpp"
#include "server/model_cache.hpp"
#include "server/secrets.hpp"
#include "server/store/open_storage.hpp"
#include "server/store/orphan_sweep.hpp"
#include "server/periodic_task.hpp"

namespace meshmark::server {

namespace {

// Every connection needs a descriptor: raise the soft limit to the hard one, and keep the
// connection cap below it (with room for the database, blobs and uploads).
std::size_t connection_cap(std::size_t wanted) {
  rlimit limit{};
  if (::getrlimit(RLIMIT_NOFILE, &limit) != 0) return wanted;
  if (limit.rlim_cur < limit.rlim_max) {
    limit.rlim_cur = limit.rlim_max;
    ::setrlimit(RLIMIT_NOFILE, &limit);
    ::getrlimit(RLIMIT_NOFILE, &limit);
  }
  const std::size_t reserve = 128;
  const std::size_t room = limit.rlim_cur > reserve * 2 ? static_cast<std::size_t>(limit.rlim_cur) - reserve : reserve;
  if (wanted > room) spdlog::warn("at most {} connections: the descriptor limit is {}", room, limit.rlim_cur);
  return std::min(wanted, room);
}

HttpServerOptions http_options(const DaemonConfig& config) {
  HttpServerOptions o;
  o.host = config.host;
  o.port = config.port;
  o.handler_threads = config.http_threads;
  o.max_connections = connection_cap(config.max_connections);
  o.max_connections_per_client = config.max_connections_per_client;
  o.max_body_bytes = config.max_upload_bytes;
  o.upload_dir = config.data_dir / "uploads";
  return o;
}

// The data folder is its owner's alone (folders 0700, files 0600: the meshes and the recipient ↔
// payload table are private), and what a killed daemon left half-written (`.tmp-*` files of
// atomic writes, streamed uploads) goes. Runs under the folder's lock.
void secure_and_sweep(const std::filesystem::path& data) {
  namespace fs = std::filesystem;
  fs::remove_all(data / "uploads");
  fs::permissions(data, fs::perms::owner_all, fs::perm_options::replace);
  std::vector<fs::path> half_written;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(data)) {
    if (e.is_symlink()) continue;
    if (e.is_regular_file() && e.path().filename().string().starts_with(kAtomicTemporaryPrefix))
      half_written.push_back(e.path());
    else if (e.is_directory()) fs::permissions(e.path(), fs::perms::owner_all, fs::perm_options::replace);
    else if (e.is_regular_file())
      fs::permissions(e.path(), fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
  }
  for (const fs::path& p : half_written) fs::remove(p);
  if (!half_written.empty()) spdlog::info("removed {} half-written file(s) a previous run left", half_written.size());
}

void sweep_orphans(Store& store, BlobStore& blobs, const Clock& clock) {
  try {
    const SweepReport r = sweep_orphan_blobs(store, blobs, clock, kOrphanGrace);
    if (r.removed > 0) spdlog::info("removed {} of {} blobs no record names", r.removed, r.examined);
  } catch (const std::exception& e) {  // tried again at the next sweep
    spdlog::warn("orphan sweep: {}", e.what());
  }
}

// Sweeps every --orphan-sweep-minutes (never with 0).
std::optional<PeriodicTask> orphan_sweeper(const DaemonConfig& config, Store& store, BlobStore& blobs,
                                           const Clock& clock) {
  if (config.orphan_sweep_minutes == 0) return std::nullopt;
  return std::optional<PeriodicTask>(std::in_place, std::chrono::minutes(config.orphan_sweep_minutes),
                                     [&store, &blobs, &clock] { sweep_orphans(store, blobs, clock); });
}

}  // namespace

int run_daemon(const DaemonConfig& config) {
  // Signals go to one waiting thread: block them before any thread starts.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  ::umask(077);  // every file the daemon makes is its user's alone
  std::filesystem::create_directories(config.data_dir);
  const DataDirLock lock(config.data_dir);  // before anything in the folder is touched
  secure_and_sweep(config.data_dir);
  const DaemonSecrets secrets = load_secrets(config);
  bool created = false;
  const Lease lease{"mmd_" + load_or_create_secret(config.data_dir / "instance-id", 8, created),
                    std::chrono::seconds(config.lease_seconds)};
  spdlog::info("instance {} (its jobs' leases last {} s)", lease.owner, config.lease_seconds);

  const Clock& clock = system_clock();
  const std::unique_ptr<Store> store_owned = open_store(config.store, config.data_dir, clock);
  const std::unique_ptr<BlobStore> blobs_owned = open_blob_store(config.blobs, config.data_dir);
  Store& store = *store_owned;
  BlobStore& blobs = *blobs_owned;
  spdlog::info("records in {}, meshes in {}", describe_location(config.store), describe_location(config.blobs));
  check_master_key(store, secrets.master_key);
  Metrics metrics;
  MemoryBudget memory(config.memory_ceiling_mb << 20);
  spdlog::info("memory ceiling: {} MiB for uploads, jobs and cached models", config.memory_ceiling_mb);
  ModelCache models(blobs, config.model_cache, memory);
  std::atomic<bool> draining{false};
  JobRunner runner({store, blobs, models, memory, metrics, clock, lease.owner}, config, secrets.master_key);
  JobQueue::Options queue_options;
  queue_options.owner_share = config.owner_queue_share;
  if (shared_store(config.store)) {  // an idle worker takes a busy peer's queued work
    queue_options.claim = [&store, &clock, &lease]() -> std::optional<QueuedJob> {
      const auto job = store.claim_queued_job(lease.owner, lease.until(clock));
      return job ? std::optional(queued_job(*job)) : std::nullopt;
    };
    queue_options.claim_interval = std::chrono::seconds(1);  // and at once when another announces work
    queue_options.announce = [&store] { store.announce_claimable_jobs(); };
  }
  JobQueue queue(
      config.max_queue, config.workers,
      [&runner](const std::string& id, const std::atomic<bool>& cancel) { runner.run(id, cancel); }, queue_options);
  ApiContext context{store,    blobs, queue, models, memory, metrics, config, secrets.admin_token, secrets.master_key,
                     draining, clock, lease};
  ApiHandler api(context);
  HttpServer http(http_options(config), api);
  // Listen first: if the port is taken, stop before any worker starts on a recovered job.
  const int port = http.bind();

  const std::vector<QueuedJob> unfinished = recover_jobs(store, clock, lease, true);
  for (const QueuedJob& job : unfinished) queue.push_recovered(job);
  if (!unfinished.empty()) spdlog::info("recovered {} job(s) left unfinished", unfinished.size());
  const LeaseKeeper leases(store, queue, clock, lease);
  const std::unique_ptr<Subscription> announced = store.watch_claimable_jobs([&queue] { queue.wake_idle(); });
  const std::optional<PeriodicTask> sweeper = orphan_sweeper(config, store, blobs, clock);
  std::printf("meshmarkd listening on http://%s:%d (data in %s, %d workers)\n", config.host.c_str(), port,
              config.data_dir.c_str(), config.workers);
  std::fflush(stdout);

  // SIGTERM: refuse new work (503, /readyz unready) but keep answering job polls while the
  // running jobs finish, then stop listening.
  std::atomic<bool> finished{true};
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&signals, &signal);
    spdlog::info("signal {}: draining (no new work; running jobs may finish for {} s)", signal,
                 config.shutdown_grace_seconds);
    draining = true;
    finished = queue.drain(std::chrono::seconds(config.shutdown_grace_seconds));
    http.stop();
  });
  http.run();  // returns after stop()
  waiter.join();
  if (!finished) {
    // Their jobs stay 'running' in the store, which is durable at every commit: the next start
    // runs them again, as after a crash. Joining the workers would wait for them instead.
    spdlog::warn("jobs still running at the end of the grace period: they run again after the next start");
    spdlog::shutdown();
    std::_Exit(0);
  }
  spdlog::info("stopped");
  return 0;
}

}  // namespace meshmark::server
