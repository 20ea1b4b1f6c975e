#include "server/clock.hpp"

#include <gtest/gtest.h>

namespace meshmark::server {
namespace {

TEST(Iso8601, WhatIsWrittenIsReadBackToTheMillisecond) {
  const auto t = std::chrono::sys_days{std::chrono::year{2026} / 12 / 4} + std::chrono::hours(16) +
                 std::chrono::minutes(5) + std::chrono::milliseconds(7'123);
  EXPECT_EQ(iso8601(t), "2026-12-04T16:05:07.123Z");
  EXPECT_EQ(parse_iso8601(iso8601(t)), t);
}

TEST(Iso8601, AnObjectStoresFormsAreRead) {
  const auto whole = parse_iso8601("2026-12-04T16:05:07Z");  // no fraction
  ASSERT_TRUE(whole);
  EXPECT_EQ(parse_iso8601("2026-12-04T16:05:07.5Z"), *whole + std::chrono::milliseconds(500));
  EXPECT_EQ(parse_iso8601("2026-12-04T16:05:07.123456Z"), *whole + std::chrono::milliseconds(123));
}

TEST(Iso8601, WhatIsNotATimeIsNone) {
  for (const char* text : {"", "yesterday", "2026-12-04", "2026-12-04T16:05:07", "2026-12-04T16:05:07+01:00",
                           "2026-12-04T16:05:07.Z", "2026-12-04T16:05:07.123Zjunk"})
    EXPECT_FALSE(parse_iso8601(text)) << text;
}

}  // namespace
}  // namespace meshmark::server
