#include "server/http/connection_counts.hpp"

namespace meshmark::server {

ConnectionCounts::Admission ConnectionCounts::admit(const std::string& client) {
  std::lock_guard lock(mutex_);
  if (total_ >= max_total_) return Admission::server_full;
  std::size_t& mine = per_client_[client];
  if (mine >= max_per_client_) {
    if (mine == 0) per_client_.erase(client);
    return Admission::client_full;
  }
  ++mine;
  ++total_;
  return Admission::admitted;
}

void ConnectionCounts::release(const std::string& client) {
  std::lock_guard lock(mutex_);
  const auto it = per_client_.find(client);
  if (it == per_client_.end()) return;
  if (--it->second == 0) per_client_.erase(it);
  --total_;
}

std::size_t ConnectionCounts::total() const {
  std::lock_guard lock(mutex_);
  return total_;
}

std::size_t ConnectionCounts::from(const std::string& client) const {
  std::lock_guard lock(mutex_);
  const auto it = per_client_.find(client);
  return it == per_client_.end() ? 0 : it->second;
}

}  // namespace meshmark::server
