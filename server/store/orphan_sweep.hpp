#pragma once
// Blobs nobody names any more: a request writes its blobs before the row that names them, so a
// crash or a failed insert between the two leaves files no record refers to, and so does a delete
// whose blob removal failed. The sweep removes each blob in the models/ and jobs/ folders whose
// record is gone, once it is older than a grace period (far longer than the moments between a
// blob and its row). Sweeps from several daemons at once are harmless; anything else in the store
// is left alone.

#include <chrono>
#include <cstddef>

#include "server/clock.hpp"
#include "server/store/blob_store.hpp"
#include "server/store/store.hpp"

namespace meshmark::server {

/// What the daemon waits before a blob without a record is taken for an orphan.
inline constexpr std::chrono::hours kOrphanGrace{1};

struct SweepReport {
  std::size_t examined = 0;  ///< blobs listed
  std::size_t removed = 0;
};

SweepReport sweep_orphan_blobs(Store& store, BlobStore& blobs, const Clock& clock, std::chrono::seconds grace);

}  // namespace meshmark::server
