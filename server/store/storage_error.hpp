#pragma once
// A failure of the daemon's storage (database or blobs), by what a caller can do about it:
//   full        — the disk or quota is full: clients see 507, workers retry later;
//   unavailable — the storage did not answer (busy, connection lost, timed out): clients see 503
//                 with Retry-After, workers retry later;
//   permanent   — anything else (corruption, a refused statement): 500, no retry.
// The message is for the log only (it names server paths and statements).

#include <stdexcept>
#include <string>

namespace meshmark::server {

class StorageError : public std::runtime_error {
 public:
  enum class Kind { full, unavailable, permanent };
  StorageError(const std::string& what, Kind kind) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const noexcept { return kind_; }
  bool full() const noexcept { return kind_ == Kind::full; }
  /// Trying again later may succeed.
  bool retryable() const noexcept { return kind_ != Kind::permanent; }

 private:
  Kind kind_;
};

}  // namespace meshmark::server
