#include "server/clock.hpp"

#include <cctype>
#include <cstdio>
#include <string>
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

std::optional<Clock::TimePoint> parse_iso8601(const std::string& text) {
  std::tm utc{};
  int millis = 0, used = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d%n", &utc.tm_year, &utc.tm_mon, &utc.tm_mday, &utc.tm_hour,
                  &utc.tm_min, &utc.tm_sec, &used) != 6)
    return std::nullopt;
  std::string rest = text.substr(static_cast<std::size_t>(used));
  if (rest.size() >= 2 && rest[0] == '.') {  // a fraction: its first three digits are milliseconds
    std::size_t digits = 1;
    while (digits < rest.size() && std::isdigit(static_cast<unsigned char>(rest[digits]))) ++digits;
    if (digits == 1) return std::nullopt;
    millis = std::stoi((rest.substr(1, digits - 1) + "00").substr(0, 3));
    rest = rest.substr(digits);
  }
  if (rest != "Z") return std::nullopt;
  utc.tm_year -= 1900;
  utc.tm_mon -= 1;
  const std::time_t seconds = timegm(&utc);
  if (seconds == -1) return std::nullopt;
  return std::chrono::system_clock::from_time_t(seconds) + std::chrono::milliseconds(millis);
}

}  // namespace meshmark::server
