// Naming the copy a suspect is, on a model made here.

#include "core/watermark/trace_copies.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

const PreparedModel& traced_sphere() {
  static const PreparedModel m = prepare_model(test::icosphere(4));
  return m;
}

std::vector<KnownCopy> two_copies() {
  return {{bits_from_hex("1234"), Scheme::spread, WaveletType::linear_lifting},
          {bits_from_hex("beef"), Scheme::spread, WaveletType::linear_lifting}};
}

TraceOptions sixteen_bits() {
  TraceOptions options;
  options.detect.payload_bits = 16;
  return options;
}

TEST(TraceCopies, NamesTheCopyTheSuspectWasMadeFrom) {
  const auto copies = two_copies();
  const Mesh suspect = embed_watermark(traced_sphere(), "k", copies[1].payload).mesh;
  const Tracing t = trace_copies(traced_sphere(), suspect, "k", copies, sixteen_bits());
  ASSERT_TRUE(t.match);
  EXPECT_EQ(t.match->copy, 1u);
  EXPECT_TRUE(t.result.detected);
  ASSERT_EQ(t.ranked.size(), 2u);
  EXPECT_LT(t.ranked[0].log10_p_value, t.ranked[1].log10_p_value);
  EXPECT_EQ(t.readings, 1u) << "both copies share their settings with the request: one reading";
}

TEST(TraceCopies, TheOriginalMatchesNoCopy) {
  const Tracing t = trace_copies(traced_sphere(), traced_sphere().mesh, "k", two_copies(), sixteen_bits());
  EXPECT_FALSE(t.match);
  EXPECT_FALSE(t.result.detected);
}

TEST(TraceCopies, CopiesMadeWithOtherSettingsAreReadWithTheirOwn) {
  auto copies = two_copies();
  copies[0].payload = bits_from_hex("12345678");  // a 32-bit copy: a reading of its own
  WatermarkOptions options;
  const Mesh suspect = embed_watermark(traced_sphere(), "k", copies[0].payload, options).mesh;
  const Tracing t = trace_copies(traced_sphere(), suspect, "k", copies, sixteen_bits());
  EXPECT_EQ(t.readings, 2u);
  ASSERT_TRUE(t.match);
  EXPECT_EQ(t.match->copy, 0u);
  // The copy was the one candidate of its reading; its p-value is charged for the two readings.
  ASSERT_EQ(t.result.candidate_log10_p.size(), 1u);
  EXPECT_NEAR(t.match->log10_p_value, t.result.candidate_log10_p[0] + std::log10(2.0), 1e-12);
}

}  // namespace
}  // namespace meshmark
