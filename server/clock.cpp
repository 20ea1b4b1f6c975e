#include "server/clock.hpp"

#include <cstdio>
#include <ctime>

namespace meshmark::server {

std::string Clock::now_iso8601() const { return iso8601(now()); }

const Clock& system_clock() {
  static const SystemClock clock;
  return clock;
}

std::string iso8601(Clock::TimePoint t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(t.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char buffer[64];  // room for any int the format could print: -Wformat-truncation
  std::snprintf(buffer, sizeof buffer, "%04d-%02d-%02dT%02d:%02d:%02d.%03lldZ", utc.tm_year + 1900, utc.tm_mon + 1,
                utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, static_cast<long long>(millis));
  return buffer;
}

}  // namespace meshmark::server
