#pragma once
// The one clock every timestamp the daemon writes comes from: the store, the runner, the
// handlers and the recovery are all given the same one, so a test can hold time still or move
// it (leases, retries) without sleeping.

#include <chrono>
#include <optional>
#include <string>

namespace meshmark::server {

class Clock {
 public:
  using TimePoint = std::chrono::system_clock::time_point;
  virtual ~Clock() = default;
  virtual TimePoint now() const = 0;
  /// Now as an ISO 8601 UTC timestamp with milliseconds ("2026-11-21T09:30:00.123Z"): sortable.
  std::string now_iso8601() const;
};

/// The system's wall clock.
class SystemClock : public Clock {
 public:
  TimePoint now() const override { return std::chrono::system_clock::now(); }
};
const Clock& system_clock();

/// `t` as ISO 8601 UTC with milliseconds.
std::string iso8601(Clock::TimePoint t);
/// "2026-11-21T09:30:00.123Z" (the fraction optional) back to a time; nullopt if it is not one.
std::optional<Clock::TimePoint> parse_iso8601(const std::string& text);

}  // namespace meshmark::server
