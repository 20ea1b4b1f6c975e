#pragma once
// A failure of the daemon's storage (database or blob files). `full()` says the disk or quota is
// full, which clients see as 507 and workers retry; the message is for the log only (it names
// server paths).

#include <stdexcept>
#include <string>

namespace meshmark::server {

class StorageError : public std::runtime_error {
 public:
  StorageError(const std::string& what, bool full) : std::runtime_error(what), full_(full) {}
  bool full() const noexcept { return full_; }

 private:
  bool full_;
};

}  // namespace meshmark::server
