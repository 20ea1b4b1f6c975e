#include "server/daemon.hpp"

#include "server/http/httplib.hpp"
#include <signal.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "server/http/api.hpp"
#include "server/jobs/job_queue.hpp"
#include "server/jobs/job_runner.hpp"
#include "server/jobs/recover_jobs.hpp"
#include "server/model_cache.hpp"
#include "server/secrets.hpp"
#include "server/store/blob_store.hpp"
#include "server/store/sqlite_store.hpp"
#include "server/clock.hpp"

namespace meshmark::server {

namespace {

std::string admin_token(const DaemonConfig& config) {
  if (!config.admin_token.empty()) {
    spdlog::info("admin token: taken from MESHMARK_ADMIN_TOKEN");
    return config.admin_token;
  }
  bool created = false;
  const auto path = config.data_dir / "admin-token";
  const std::string token = load_or_create_secret(path, 32, created);
  spdlog::info("admin token: {} {} (mode 0600)", created ? "generated into" : "read from", path.string());
  return token;
}

}  // namespace

int run_daemon(const DaemonConfig& config) {
  // Signals go to one waiting thread: block them before any thread starts.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  std::filesystem::create_directories(config.data_dir);
  std::filesystem::remove_all(config.data_dir / "uploads");
  const std::string admin = admin_token(config);
  bool created = false;
  const std::string master_key = load_or_create_secret(config.data_dir / "master.key", 32, created);
  if (created) spdlog::info("master key: generated into {} (mode 0600); back it up with the data", (config.data_dir / "master.key").string());

  // Listen first: if the port is taken, stop before any worker starts on a recovered job.
  httplib::Server http;
  http.new_task_queue = [threads = config.http_threads] { return new httplib::ThreadPool(static_cast<size_t>(threads)); };
  // A client that goes quiet for 10 s loses its connection: slow senders must not hold the
  // HTTP threads (each read waits at most this long; a steady upload is never cut).
  http.set_read_timeout(10, 0);
  http.set_write_timeout(30, 0);
  // cpp-httplib writes headers and body separately: without TCP_NODELAY, Nagle's algorithm and the
  // client's delayed ACK stall every small response by ~40 ms (measured: /livez at 300 req/s).
  http.set_tcp_nodelay(true);
  http.set_keep_alive_max_count(100);
  int port = config.port;
  if (port == 0) port = http.bind_to_any_port(config.host);
  else if (!http.bind_to_port(config.host, port)) port = -1;
  if (port < 0) {
    spdlog::error("cannot listen on {}:{}", config.host, config.port);
    return 1;
  }

  SqliteStore store(config.data_dir / "meshmark.db");
  LocalBlobStore blobs(config.data_dir / "blobs");
  Metrics metrics;
  ModelCache models(blobs, config.model_cache);
  JobRunner runner(store, blobs, models, metrics, config, master_key);
  JobQueue queue(config.max_queue, config.workers,
                 [&runner](const std::string& id, const std::atomic<bool>& cancel) { runner.run(id, cancel); });
  const std::vector<std::string> unfinished = recover_jobs(store);
  for (const std::string& id : unfinished) queue.push_recovered(id);
  if (!unfinished.empty()) spdlog::info("recovered {} job(s) left unfinished", unfinished.size());

  std::atomic<bool> draining{false};
  ApiContext context{store, blobs, queue, models, metrics, config, admin, draining};
  install_api(http, context);
  std::printf("meshmarkd listening on http://%s:%d (data in %s, %d workers)\n", config.host.c_str(), port,
              config.data_dir.c_str(), config.workers);
  std::fflush(stdout);

  // SIGTERM: refuse new work (503, /readyz unready) but keep answering job polls while the
  // running jobs finish, then stop listening.
  std::atomic<bool> finished{true};
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&signals, &signal);
    spdlog::info("signal {}: draining (no new work; running jobs may finish for {} s)", signal, config.shutdown_grace_seconds);
    draining = true;
    finished = queue.drain(std::chrono::seconds(config.shutdown_grace_seconds));
    http.stop();
  });
  http.listen_after_bind();  // returns after stop()
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
