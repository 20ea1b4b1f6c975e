// The carrier cache kept with a prepared model: it hands out what a fresh build would, keeps a
// bounded number of plans, and a copy of the model never reads its original's cache.

#include "core/watermark/carrier_cache.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "core/watermark/known_payload_scores.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// 2,562 vertices: 16 and 32 bits, on more than one band.
PreparedModel sphere_model() { return prepare_model(test::icosphere(4)); }

void expect_same_plan(const SpreadPlan& a, const SpreadPlan& b) {
  EXPECT_EQ(a.coefficient, b.coefficient);
  EXPECT_EQ(a.bit, b.bit);
  EXPECT_EQ(a.band, b.band);
  EXPECT_EQ(a.weight, b.weight);
  EXPECT_EQ(a.levels, b.levels);
}

TEST(CarrierCache, APlanFromTheCacheIsTheOneMadeAfresh) {
  const PreparedModel model = sphere_model();
  const WatermarkOptions options;
  const auto cached = carrier_cache(model).plan(model, "k", 16, options, 0);
  const CarrierField field(model, options.wavelet, 0);
  expect_same_plan(*cached, make_spread_plan(model, field, "k", 16, options));
  EXPECT_EQ(cached, carrier_cache(model).plan(model, "k", 16, options, 0)) << "asked again: built again";
}

// A pattern from the cache is the field a fresh synthesis gives; asked again for the same plan and
// codeword it is the one kept, and another codeword or plan gets its own.
TEST(CarrierCache, APatternFromTheCacheIsTheSynthesisOfItsCodeword) {
  const PreparedModel model = sphere_model();
  CarrierCache& cache = carrier_cache(model);
  const CarrierField& field = cache.field(model, WaveletType::linear_lifting, 0);
  const auto plan = cache.plan(model, "k", 16, {}, 0);
  Bits codeword(static_cast<std::size_t>(plan->coded_bits), 0);
  for (std::size_t i = 0; i < codeword.size(); i += 3) codeword[i] = 1;
  const auto pattern = cache.pattern(plan, field, codeword);
  EXPECT_EQ(*pattern, field.to_vertices(plan_coefficients(*plan, signs_of(codeword), static_cast<int>(field.size()))));
  EXPECT_EQ(pattern, cache.pattern(plan, field, codeword)) << "asked again: made again";
  Bits other = codeword;
  other[1] ^= 1;
  EXPECT_NE(*pattern, *cache.pattern(plan, field, other));
  EXPECT_NE(pattern, cache.pattern(cache.plan(model, "another key", 16, {}, 0), field, codeword));
}

TEST(CarrierCache, KeysLengthsAndBandRulesEachGetTheirOwnPlan) {
  const PreparedModel model = sphere_model();
  CarrierCache& cache = carrier_cache(model);
  WatermarkOptions one_band;
  one_band.max_bands = 1;
  const auto plain = cache.plan(model, "k", 16, {}, 0);
  EXPECT_NE(plain->bit, cache.plan(model, "another key", 16, {}, 0)->bit);
  EXPECT_NE(plain->coded_bits, cache.plan(model, "k", 32, {}, 0)->coded_bits);
  WatermarkOptions wider;
  wider.min_support_vertices *= 4;
  EXPECT_NE(plain, cache.plan(model, "k", 16, one_band, 0)) << "another band rule shared the plan";
  EXPECT_NE(plain->levels, cache.plan(model, "k", 16, wider, 0)->levels);
}

TEST(CarrierCache, KeepsOnlyTheMostRecentPlans) {
  const PreparedModel model = sphere_model();
  CarrierCache& cache = carrier_cache(model);
  const auto first = cache.plan(model, "key 0", 16, {}, 0);
  for (std::size_t k = 1; k <= CarrierCache::kPlansKept; ++k) cache.plan(model, "key " + std::to_string(k), 16, {}, 0);
  const auto again = cache.plan(model, "key 0", 16, {}, 0);
  EXPECT_NE(first, again) << "more plans were asked for than are kept, yet the oldest was still there";
  expect_same_plan(*first, *again);
}

TEST(CarrierCache, ThreadsAskingAtOnceGetOnePlan) {
  const PreparedModel model = sphere_model();
  std::vector<std::shared_ptr<const SpreadPlan>> plans(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < plans.size(); ++t)
    threads.emplace_back([&, t] { plans[t] = carrier_cache(model).plan(model, "k", 16, {}, 1); });
  for (std::thread& t : threads) t.join();
  for (const auto& plan : plans) expect_same_plan(*plan, *plans.front());
  EXPECT_EQ(carrier_cache(model).plan(model, "k", 16, {}, 1), carrier_cache(model).plan(model, "k", 16, {}, 1));
}

TEST(CarrierCache, ACopyOfAModelStartsWithAnEmptyCacheOfItsOwn) {
  std::optional<PreparedModel> original(sphere_model());
  const CarrierField& field = carrier_cache(*original).field(*original, WatermarkOptions{}.wavelet, 0);
  const auto plan = carrier_cache(*original).plan(*original, "k", 16, {}, 0);
  const PreparedModel copy = *original;
  EXPECT_NE(&carrier_cache(copy), &carrier_cache(*original));
  EXPECT_NE(&carrier_cache(copy).field(copy, WatermarkOptions{}.wavelet, 0), &field);
  original.reset();  // what the original's cache held referred to it; the copy's must not
  const CarrierField& own = carrier_cache(copy).field(copy, WatermarkOptions{}.wavelet, 0);
  EXPECT_EQ(own.size(), copy.sample_count());
  expect_same_plan(*carrier_cache(copy).plan(copy, "k", 16, {}, 0), *plan);
}

}  // namespace
}  // namespace meshmark
