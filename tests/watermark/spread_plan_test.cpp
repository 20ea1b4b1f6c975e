// The spread plan on a model made here (an icosphere): who carries which bit, and with which chip.

#include "core/watermark/spread_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

const PreparedModel& sphere_model() {
  static const PreparedModel m = prepare_model(test::icosphere(4));
  return m;
}

// The icosphere stretched along x: another model (another digest), the same connectivity.
const PreparedModel& stretched_model() {
  static const PreparedModel m = [] {
    Mesh mesh = test::icosphere(4);
    mesh.V.col(0) *= 1.3;
    return prepare_model(mesh);
  }();
  return m;
}

SpreadPlan plan_of(const PreparedModel& model, const std::string& key, int bits = 32) {
  const CarrierField field(model, WatermarkOptions{}.wavelet, 0);
  return make_spread_plan(model, field, key, bits, WatermarkOptions{});
}

TEST(SpreadPlan, EveryCodedBitGetsAnEqualShareOfEveryBand) {
  const SpreadPlan plan = plan_of(sphere_model(), "k");
  ASSERT_FALSE(plan.levels.empty());
  for (std::size_t b = 0; b < plan.levels.size(); ++b) {
    std::vector<int> per_bit(static_cast<std::size_t>(plan.coded_bits), 0);
    for (std::size_t k = 0; k < plan.band.size(); ++k)
      if (plan.band[k] == static_cast<int>(b)) ++per_bit[static_cast<std::size_t>(plan.bit[k])];
    const auto [least, most] = std::minmax_element(per_bit.begin(), per_bit.end());
    EXPECT_LE(*most - *least, 1) << "band " << plan.levels[b];
    EXPECT_GE(*least, 1) << "band " << plan.levels[b] << " leaves a coded bit without a carrier";
  }
}

TEST(SpreadPlan, TheSameKeyAndModelGiveTheSamePlan) {
  const SpreadPlan a = plan_of(sphere_model(), "k"), b = plan_of(sphere_model(), "k");
  EXPECT_EQ(a.coefficient, b.coefficient);
  EXPECT_EQ(a.bit, b.bit);
  EXPECT_EQ(a.weight, b.weight);
}

TEST(SpreadPlan, AnotherKeyDealsTheCarriersDifferently) {
  const SpreadPlan a = plan_of(sphere_model(), "k"), b = plan_of(sphere_model(), "another key");
  EXPECT_NE(a.bit, b.bit);
}

TEST(SpreadPlan, AnotherModelGetsUnrelatedChipsUnderTheSameKey) {
  const SpreadPlan a = plan_of(sphere_model(), "k"), b = plan_of(stretched_model(), "k");
  ASSERT_EQ(a.coefficient.size(), b.coefficient.size()) << "same connectivity, same carriers";
  ASSERT_NE(chip_label("spread", sphere_model()), chip_label("spread", stretched_model()));
  // The chips (signs of the weights) of the carriers both plans put at one coefficient agree
  // about half the time, as unrelated signs do.
  std::map<int, double> sign_a;
  for (std::size_t k = 0; k < a.coefficient.size(); ++k)
    sign_a[a.coefficient[k]] = a.weight[static_cast<Eigen::Index>(k)] > 0;
  int agree = 0, n = 0;
  for (std::size_t k = 0; k < b.coefficient.size(); ++k)
    if (auto it = sign_a.find(b.coefficient[k]); it != sign_a.end()) {
      agree += it->second == (b.weight[static_cast<Eigen::Index>(k)] > 0);
      ++n;
    }
  ASSERT_GT(n, 100);
  EXPECT_GT(agree, n / 4);
  EXPECT_LT(agree, 3 * n / 4);
}

// A low-poly model (162 vertices): 16 bits are dealt on one band with fewer carriers than coded
// bits, its carriers spaced evenly over the code (no two erased coded bits in a row where half
// the bits have a carrier); longer payloads keep the strict rule and are refused.
TEST(SpreadPlan, ALowPolyMeshPuncturesAShortCodeEvenly) {
  const PreparedModel model = prepare_model(test::creature(2));
  const SpreadPlan plan = plan_of(model, "k", 16);
  ASSERT_EQ(plan.levels.size(), 1u);
  const auto carriers = static_cast<int>(plan.bit.size());
  ASSERT_LT(carriers, plan.coded_bits);
  ASSERT_GE(carriers, kMinPuncturedCoverage * plan.coded_bits);
  std::vector<int> per_bit(static_cast<std::size_t>(plan.coded_bits), 0);
  for (int bit : plan.bit) ++per_bit[static_cast<std::size_t>(bit)];
  EXPECT_EQ(*std::max_element(per_bit.begin(), per_bit.end()), 1);
  for (int b = 0; b < plan.coded_bits; ++b)
    EXPECT_TRUE(per_bit[static_cast<std::size_t>(b)] || per_bit[static_cast<std::size_t>((b + 1) % plan.coded_bits)])
        << "coded bits " << b << " and " << b + 1 << " both erased";
  EXPECT_THROW(plan_of(model, "k", kMaxPuncturedPayloadBits + 4), std::invalid_argument);
}

TEST(SpreadPlan, APayloadTooLongForTheMeshIsRefused) {
  EXPECT_THROW(plan_of(sphere_model(), "k", 4096), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark
