#pragma once
// meshmarkd: wires the store, the job queue, the model cache and the HTTP API together, recovers
// interrupted work at start, and shuts down cleanly on SIGTERM or SIGINT.

#include "server/config.hpp"

namespace meshmark::server {

/// Runs the daemon until SIGTERM/SIGINT; returns the process exit status.
int run_daemon(const DaemonConfig& config);

}  // namespace meshmark::server
