#include "server/config.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <thread>

#include "server/memory_budget.hpp"

namespace meshmark::server {

bool parse_config(int argc, char** argv, DaemonConfig& config, int& exit_code) {
  CLI::App app{"meshmarkd: the meshmark watermarking daemon (HTTP/JSON API under /v1)"};
  std::string listen = config.host + ":" + std::to_string(config.port);
  std::string data = config.data_dir.string();
  app.add_option("--listen", listen, "HOST:PORT to listen on (port 0: any free port)")
      ->envname("MESHMARK_LISTEN")
      ->capture_default_str();
  app.add_option("--data", data, "Data directory (database, meshes, secrets)")
      ->envname("MESHMARK_DATA")
      ->capture_default_str();
  app.add_option("--store", config.store,
                 "Where the records live: sqlite:PATH (default: DATA/meshmark.db) or postgresql://USER@HOST:PORT/DB "
                 "(shared by several daemons)")
      ->envname("MESHMARK_STORE");
  app.add_option("--blobs", config.blobs,
                 "Where meshes and copies live: file:PATH, a folder (default: DATA/blobs), or s3://BUCKET/PREFIX "
                 "(MESHMARK_S3_ENDPOINT, MESHMARK_S3_REGION, AWS_ACCESS_KEY_ID, AWS_SECRET_ACCESS_KEY)")
      ->envname("MESHMARK_BLOBS");
  app.add_option("--master-key-file", config.master_key_file,
                 "The master key every owner's watermark key derives from, shared by all daemons on one store "
                 "(default: DATA/master.key, generated on first start)")
      ->envname("MESHMARK_MASTER_KEY_FILE");
  app.add_option("--admin-token-file", config.admin_token_file,
                 "A file holding the admin token (MESHMARK_ADMIN_TOKEN wins; default: DATA/admin-token, generated)")
      ->envname("MESHMARK_ADMIN_TOKEN_FILE");
  app.add_option("--workers", config.workers, "Compute workers (0: one per core)")
      ->check(CLI::NonNegativeNumber)
      ->envname("MESHMARK_WORKERS")
      ->capture_default_str();
  app.add_option(
         "--threads-per-job", config.threads_per_job,
         "Threads of one job's parallel steps (0: the hardware's, at most 8; workers x this may exceed the cores)")
      ->check(CLI::Range(0, 64))
      ->envname("MESHMARK_THREADS_PER_JOB")
      ->capture_default_str();
  app.add_option("--http-threads", config.http_threads, "Threads that run request handlers")
      ->check(CLI::PositiveNumber)
      ->envname("MESHMARK_HTTP_THREADS")
      ->capture_default_str();
  app.add_option("--max-connections", config.max_connections, "Connections open at once (beyond: 503)")
      ->check(CLI::PositiveNumber)
      ->envname("MESHMARK_MAX_CONNECTIONS")
      ->capture_default_str();
  app.add_option(
         "--max-connections-per-client", config.max_connections_per_client,
         "Connections open at once from one address (beyond: 503); behind a proxy, as many as --max-connections")
      ->check(CLI::PositiveNumber)
      ->envname("MESHMARK_MAX_CONNECTIONS_PER_CLIENT")
      ->capture_default_str();
  app.add_option("--max-queue", config.max_queue, "Queued jobs at most")
      ->check(CLI::PositiveNumber)
      ->envname("MESHMARK_MAX_QUEUE")
      ->capture_default_str();
  app.add_option("--owner-queue-share", config.owner_queue_share,
                 "The share of the queue one owner may hold (at least one place): one owner's burst leaves room")
      ->check(CLI::Range(0.0, 1.0))
      ->envname("MESHMARK_OWNER_QUEUE_SHARE")
      ->capture_default_str();
  app.add_option("--max-upload-bytes", config.max_upload_bytes, "Largest request body")
      ->check(CLI::PositiveNumber)
      ->envname("MESHMARK_MAX_UPLOAD_BYTES")
      ->capture_default_str();
  app.add_option("--max-vertices", config.max_vertices, "Largest mesh")
      ->check(CLI::PositiveNumber)
      ->envname("MESHMARK_MAX_VERTICES")
      ->capture_default_str();
  app.add_option("--memory-ceiling-mb", config.memory_ceiling_mb,
                 "MiB that uploads, jobs and cached models may hold together (beyond: 503, or jobs wait); 0: "
                 "60% of the machine's memory (or of the container's limit)")
      ->check(CLI::NonNegativeNumber)
      ->envname("MESHMARK_MEMORY_CEILING_MB")
      ->capture_default_str();
  app.add_option("--job-time-limit", config.job_time_limit_seconds, "Seconds a job may run")
      ->check(CLI::PositiveNumber)
      ->envname("MESHMARK_JOB_TIME_LIMIT")
      ->capture_default_str();
  app.add_option("--model-cache", config.model_cache, "Prepared models kept in memory")
      ->check(CLI::PositiveNumber)
      ->envname("MESHMARK_MODEL_CACHE")
      ->capture_default_str();
  app.add_option("--lease-seconds", config.lease_seconds,
                 "How long a daemon's hold on its jobs lasts unrenewed: after that, another daemon on the same store "
                 "takes them over (renewed every third of it)")
      ->check(CLI::Range(3, 3600))
      ->envname("MESHMARK_LEASE_SECONDS")
      ->capture_default_str();
  app.add_option("--orphan-sweep-minutes", config.orphan_sweep_minutes,
                 "How often the blob store is swept of files no record names (older than an hour); 0: never")
      ->check(CLI::Range(0, 7 * 24 * 60))
      ->envname("MESHMARK_ORPHAN_SWEEP_MINUTES")
      ->capture_default_str();
  app.add_option("--shutdown-grace", config.shutdown_grace_seconds, "Seconds running jobs may finish after SIGTERM")
      ->check(CLI::NonNegativeNumber)
      ->envname("MESHMARK_SHUTDOWN_GRACE")
      ->capture_default_str();
  app.add_option("--log-level", config.log_level, "trace, debug, info, warn, error")
      ->envname("MESHMARK_LOG_LEVEL")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    exit_code = app.exit(e);
    return false;
  }
  const auto colon = listen.rfind(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("");
    config.host = listen.substr(0, colon);
    config.port = std::stoi(listen.substr(colon + 1));
    if (config.port < 0 || config.port > 65535) throw std::invalid_argument("");
  } catch (const std::exception&) {
    std::fprintf(stderr, "meshmarkd: --listen must be HOST:PORT, not '%s'\n", listen.c_str());
    exit_code = 2;
    return false;
  }
  config.data_dir = data;
  if (config.memory_ceiling_mb == 0) config.memory_ceiling_mb = kDefaultMemoryShare * (available_memory_bytes() >> 20);
  if (config.workers <= 0) config.workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (const char* token = std::getenv("MESHMARK_ADMIN_TOKEN")) {
    config.admin_token = token;
    // Length alone lets "aaaaaaaaaaaaaaaa" through: the characters must vary too.
    const std::size_t distinct = std::set<char>(config.admin_token.begin(), config.admin_token.end()).size();
    if (config.admin_token.size() < kMinAdminTokenLength || distinct < kMinAdminTokenDistinct) {
      std::fprintf(stderr,
                   "meshmarkd: MESHMARK_ADMIN_TOKEN must be at least %zu characters, %zu of them different (it has "
                   "%zu, %zu different); generate one, e.g. openssl rand -hex 24\n",
                   kMinAdminTokenLength, kMinAdminTokenDistinct, config.admin_token.size(), distinct);
      exit_code = 2;
      return false;
    }
  }
  return true;
}

std::size_t faces_for_vertices(std::size_t vertices) {
  // A closed triangle mesh has F = 2V − 4 + 4g faces: twice the vertices, with room for handles,
  // bounds the faces of any mesh of that many vertices.
  constexpr std::size_t kFaceLimitSlack = 64;
  return 2 * vertices + kFaceLimitSlack;
}

namespace {
// A file inside an upload (a ZIP's member, a glTF's buffer) may be this many times the upload.
constexpr std::size_t kUnpackedBytesPerUploadByte = 4;
}  // namespace

ReadOptions upload_read_options(const DaemonConfig& config, const JobControl* control) {
  ReadOptions options;
  options.max_vertices = config.max_vertices;
  options.max_faces = faces_for_vertices(config.max_vertices);
  options.max_file_bytes = kUnpackedBytesPerUploadByte * config.max_upload_bytes;
  options.control = control;
  return options;
}

}  // namespace meshmark::server
