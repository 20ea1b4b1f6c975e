#include "core/watermark/combine_evidence.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace meshmark {
namespace {

DetectResult blind_only(double blind_log10_p) {
  DetectResult r;
  r.blind_log10_p_value = blind_log10_p;
  return r;
}

TEST(CombineEvidence, TheBlindTestAloneIsTakenAsIs) {
  DetectResult r = blind_only(-9);
  combine_evidence(r, {});
  EXPECT_DOUBLE_EQ(r.log10_p_value, -9);
  EXPECT_TRUE(r.detected);
  EXPECT_EQ(r.evidence, "blind decode");
}

// A twisted copy: the blind union bound over every payload cannot reach 1e-6, the expected
// payload alone can. The decision follows the evidence, charged for the two tests made.
TEST(CombineEvidence, AnExpectedPayloadDecidesWhereTheBlindBoundCannot) {
  DetectResult r = blind_only(-2);
  r.expected_log10_p_value = -22;
  DetectOptions options;
  options.expected = Bits(64, true);
  combine_evidence(r, options);
  EXPECT_TRUE(r.detected);
  EXPECT_EQ(r.evidence, "expected payload");
  EXPECT_NEAR(r.log10_p_value, -22 + std::log10(2.0), 1e-12);
  ASSERT_TRUE(r.payload.has_value());
  EXPECT_EQ(*r.payload, *options.expected);
}

TEST(CombineEvidence, EveryTestMadeIsChargedForEvenWhenItLoses) {
  DetectResult r = blind_only(-10);
  r.expected_log10_p_value = 0;
  r.candidate_log10_p = {-1, -0.5};
  combine_evidence(r, {});
  EXPECT_NEAR(r.log10_p_value, -10 + std::log10(3.0), 1e-12);
  EXPECT_EQ(r.evidence, "blind decode");
}

TEST(CombineEvidence, AKnownCopyDecidesAndTheFieldsAgree) {
  DetectResult r = blind_only(0);
  r.candidate_log10_p = {-3, -25, -1};
  combine_evidence(r, {});
  EXPECT_TRUE(r.detected);
  EXPECT_EQ(r.evidence, "known copy");
  EXPECT_EQ(r.detected, r.p_value < DetectOptions{}.false_alarm);
}

// Evidence just short of the threshold after the charge is not a detection, and says none.
TEST(CombineEvidence, EvidenceShortOfTheThresholdAfterTheChargeIsNoDetection) {
  DetectResult r = blind_only(-6.2);
  r.expected_log10_p_value = -0.1;
  r.payload = Bits(64, false);  // a checksum match alone does not decide
  combine_evidence(r, {});
  EXPECT_FALSE(r.detected);
  EXPECT_EQ(r.evidence, "none");
  EXPECT_GT(r.p_value, 1e-6);
}

}  // namespace
}  // namespace meshmark
