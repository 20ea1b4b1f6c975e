#pragma once
// The daemon's settings: flags, then environment variables, then embedded defaults that need
// no setup.

#include <filesystem>
#include <string>

#include "core/io/read_options.hpp"

namespace meshmark::server {

struct DaemonConfig {
  std::string host = "127.0.0.1";
  int port = 8080;  ///< 0: any free port (printed at start)
  std::filesystem::path data_dir = "meshmark-data";
  std::string store;        ///< where the records live (server/store/open_storage.hpp); empty: DATA/meshmark.db
  std::string blobs;        ///< where the meshes live; empty: DATA/blobs
  int workers = 0;          ///< jobs run at once; 0: the number of cores
  int threads_per_job = 0;  ///< threads of one job's parallel steps; 0: the hardware's, at most 8
  int http_threads = 16;    ///< threads that run request handlers (sockets need none)
  std::size_t max_connections = 1024;            ///< open at once (capped by the descriptor limit)
  std::size_t max_connections_per_client = 256;  ///< open at once from one address
  std::size_t max_queue = 64;                    ///< queued jobs; beyond: 503 + Retry-After
  double owner_queue_share = 0.5;                ///< of max_queue, what one owner may hold; beyond: 503
  std::size_t max_upload_bytes = 256ull << 20;   ///< request bodies
  std::size_t max_vertices = 3'000'000;
  std::size_t memory_ceiling_mb = 0;  ///< uploads, jobs and cached models together; 0: kDefaultMemoryShare
  int job_time_limit_seconds = 900;
  std::size_t model_cache = 8;      ///< prepared models kept in memory
  int lease_seconds = 30;           ///< a job's daemon renews its hold every third of this; another takes it after
  int shutdown_grace_seconds = 60;  ///< SIGTERM: how long running jobs may finish
  int orphan_sweep_minutes = 60;    ///< how often blobs without a record are looked for; 0: never
  std::string admin_token;          ///< from MESHMARK_ADMIN_TOKEN; else admin_token_file; else DATA/admin-token
  std::filesystem::path admin_token_file;  ///< a file holding it (e.g. a Docker secret)
  std::filesystem::path master_key_file;   ///< the cluster's master key; empty: DATA/master.key, made on first start
  std::string log_level = "info";
};

/// The memory ceiling's default: this share of the machine's (or the container's) memory.
inline constexpr double kDefaultMemoryShare = 0.6;

/// The faces a mesh of that many vertices may have.
std::size_t faces_for_vertices(std::size_t vertices);

/// The reader limits for uploads and stored files: the vertex limit; ZIP entries (the inside of a
/// 3MF, or a zipped glTF) up to 4× the upload limit, as deflate shrinks meshes about that much.
ReadOptions upload_read_options(const DaemonConfig& config, const JobControl* control);

/// An admin token from the environment must be at least this long (a generated one has 64 hex digits).
inline constexpr std::size_t kMinAdminTokenLength = 16;
inline constexpr std::size_t kMinAdminTokenDistinct = 10;  ///< different characters in it

/// Parses argv and the environment (MESHMARK_LISTEN, MESHMARK_DATA, MESHMARK_WORKERS,
/// MESHMARK_ADMIN_TOKEN, ...). Returns false after printing help or an error (exit code in `exit_code`).
bool parse_config(int argc, char** argv, DaemonConfig& config, int& exit_code);

}  // namespace meshmark::server
