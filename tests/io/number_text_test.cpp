#include "core/io/number_text.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <random>

namespace meshmark {
namespace {

double parse(const std::string& text) {
  double value = 0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

TEST(CoordinateText, KeepsTheLargestPowerOfTenAtMostATenMillionthOfTheExtent) {
  EXPECT_EQ(CoordinateText(1.0).decimals(), 7);
  EXPECT_EQ(CoordinateText(0.25).decimals(), 8);
  EXPECT_EQ(CoordinateText(3000.0).decimals(), 4);
  EXPECT_EQ(CoordinateText(1e9).decimals(), 0);
  EXPECT_EQ(CoordinateText(0.0).decimals(), -1);  // no extent: shortest round trip
  EXPECT_EQ(CoordinateText(std::numeric_limits<double>::infinity()).decimals(), -1);
}

// Whatever the value and the offset, the text reads back within half a quantum and is never
// longer than the value's shortest round-trip text.
TEST(CoordinateText, ReadsBackWithinHalfAQuantumAndIsNeverLongerThanTheShortest) {
  std::mt19937 random(7);
  for (const double extent : {1e-4, 0.25, 1.0, 850.0, 2e6}) {
    const CoordinateText text(extent);
    const double quantum = std::pow(10.0, -text.decimals());
    std::uniform_real_distribution<double> value(-extent, extent);
    for (const double offset : {0.0, 5e5 * extent}) {
      for (int i = 0; i < 2000; ++i) {
        const double x = offset + value(random);
        const std::string t = text(x);
        EXPECT_LE(std::abs(parse(t) - x), 0.5 * quantum * (1 + 1e-9) + std::abs(x) * 1e-16) << t << " for " << x;
        EXPECT_LE(t.size(), number_text(x).size()) << t;
      }
    }
  }
}

// The text is the shorter of the value to the fixed decimals and its shortest round-trip text
// (the latter on a tie): the writer leaves the second out where it cannot win, and must choose
// as if it had made both, over values of every magnitude and short decimals alike.
TEST(CoordinateText, IsTheShorterOfTheFixedAndTheShortestText) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-12, 4), short_mantissa(1, 9999);
  std::uniform_int_distribution<long long> whole(-99999999, 99999999);
  for (const double extent : {1.0, 0.25, 3000.0, 1e9}) {
    const CoordinateText text(extent);
    const double quantum = std::pow(10.0, -text.decimals());
    for (int i = 0; i < 20000; ++i) {
      double x = mantissa(random) * extent * std::pow(10.0, exponent(random) % 4);
      if (i % 3 == 1)  // a short decimal (3.21e-06): its shortest text can beat the fixed one
        x = parse(std::to_string(short_mantissa(random)) + "e" + std::to_string(exponent(random) - 3));
      if (i % 3 == 2)  // about halfway between two fixed texts: the rounding must still be the reader's
        x = (static_cast<double>(whole(random)) + 0.5) * quantum;
      char fixed[64];
      const auto end = std::to_chars(fixed, fixed + sizeof fixed, x, std::chars_format::fixed, text.decimals()).ptr;
      std::string f(fixed, end);
      if (f.find('.') != std::string::npos) f.erase(f.find_last_not_of('0') + 1);
      if (!f.empty() && f.back() == '.') f.pop_back();
      if (f == "-0") f = "0";
      const std::string shortest = number_text(x);
      EXPECT_EQ(text(x), f.size() < shortest.size() ? f : shortest) << x << " at extent " << extent;
    }
  }
}

TEST(CoordinateText, ShortValuesKeepTheirExactTextAndZeroHasNoSign) {
  const CoordinateText text(1.0);
  EXPECT_EQ(text(0.5), "0.5");
  EXPECT_EQ(text(0.1), "0.1");
  EXPECT_EQ(text(-3.0), "-3");
  EXPECT_EQ(text(0.123456789012), "0.1234568");
  EXPECT_EQ(text(-0.00000000001), "0");
  EXPECT_EQ(text(-0.0), "0");
  EXPECT_EQ(text(std::numeric_limits<double>::infinity()), "inf");
}

TEST(NumberText, IsTheShortestRoundTrip) {
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(parse(number_text(0.123456789012345678)), 0.123456789012345678);
  EXPECT_EQ(number_text(0.1f), "0.1");
}

}  // namespace
}  // namespace meshmark
