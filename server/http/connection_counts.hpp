#pragma once
// Connections open at once, in total and per client address, so that one client holding many
// sockets (idle or slow) leaves room for every other.

#include <cstddef>
#include <mutex>
#include <string>
#include <unordered_map>

namespace meshmark::server {

class ConnectionCounts {
 public:
  ConnectionCounts(std::size_t max_total, std::size_t max_per_client)
      : max_total_(max_total), max_per_client_(max_per_client) {}

  enum class Admission { admitted, server_full, client_full };
  /// Counts a new connection from `client` unless a cap is reached.
  Admission admit(const std::string& client);
  /// Forgets a connection admit() counted.
  void release(const std::string& client);

  std::size_t total() const;
  std::size_t from(const std::string& client) const;

 private:
  const std::size_t max_total_, max_per_client_;
  mutable std::mutex mutex_;
  std::size_t total_ = 0;
  std::unordered_map<std::string, std::size_t> per_client_;
};

}  // namespace meshmark::server
