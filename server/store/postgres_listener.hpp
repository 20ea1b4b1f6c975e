#pragma once
// PostgreSQL's LISTEN on a connection of its own, for as long as the object lives: after each
// commit that NOTIFYed the channel, `heard` is called on the listener's thread. Bursts are
// coalesced (at most one call per kListenerSpacing); a lost connection is reopened with growing
// pauses, and `heard` is called once it is back, for what may have been announced meanwhile.

#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "server/store/subscription.hpp"

namespace meshmark::server {

inline constexpr std::chrono::milliseconds kListenerSpacing{20};

class PostgresListener : public Subscription {
 public:
  PostgresListener(std::string conninfo, std::string channel, std::function<void()> heard);
  ~PostgresListener() override;
  PostgresListener(const PostgresListener&) = delete;
  PostgresListener& operator=(const PostgresListener&) = delete;

 private:
  void listen_while_connected();
  // Waits up to `pause` or until the listener is stopped; false when stopped.
  bool pause_unless_stopped(std::chrono::milliseconds pause) const;

  const std::string conninfo_, channel_;
  const std::function<void()> heard_;
  int stop_pipe_[2] = {-1, -1};  // written once, to end a poll at once
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace meshmark::server
