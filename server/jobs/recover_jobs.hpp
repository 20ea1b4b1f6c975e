#pragma once
// What happens, at start-up, to work a crash or a restart interrupted.

#include <string>
#include <vector>

#include "server/store/store.hpp"

namespace meshmark::server {

/// A job is tried at most this many times; then it is marked failed rather than run again.
constexpr int kMaxJobAttempts = 3;

/// Ends a job whose cancel was acknowledged (and, for a prepare job, fails its model).
void finish_canceled(Store& store, JobRecord job);

/// Puts jobs left 'running' back to 'queued' (or marks them 'failed', and a model being prepared
/// with them, after kMaxJobAttempts), and returns the ids of all queued jobs, oldest first.
std::vector<std::string> recover_jobs(Store& store);

}  // namespace meshmark::server
