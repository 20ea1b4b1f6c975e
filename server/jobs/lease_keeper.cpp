#include "server/jobs/lease_keeper.hpp"

#include <spdlog/spdlog.h>

namespace meshmark::server {

LeaseKeeper::LeaseKeeper(Store& store, JobQueue& queue, const Clock& clock, Lease lease)
    : store_(store),
      queue_(queue),
      clock_(clock),
      lease_(std::move(lease)),
      heartbeat_(std::chrono::duration_cast<std::chrono::milliseconds>(lease_.duration) / 3, [this] { beat(); }) {}

void LeaseKeeper::beat() {
  try {
    store_.renew_leases(lease_.owner, lease_.until(clock_));
    const std::vector<QueuedJob> taken = recover_jobs(store_, clock_, lease_, false);
    for (const QueuedJob& job : taken) queue_.push_recovered(job);
    if (!taken.empty()) spdlog::info("took over {} job(s) whose daemon stopped renewing them", taken.size());
  } catch (const std::exception& e) {  // the store is away: try again at the next beat
    spdlog::warn("leases: {}", e.what());
  }
}

}  // namespace meshmark::server
