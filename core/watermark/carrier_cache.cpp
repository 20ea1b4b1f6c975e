#include "core/watermark/carrier_cache.hpp"

#include <cstdio>

#include "core/util/keyed_random.hpp"
#include "core/watermark/known_payload_scores.hpp"

namespace meshmark {

CarrierCacheSlot::CarrierCacheSlot() : cache(std::make_unique<CarrierCache>()) {}
CarrierCacheSlot::~CarrierCacheSlot() = default;
CarrierCacheSlot::CarrierCacheSlot(const CarrierCacheSlot&) : CarrierCacheSlot() {}
CarrierCacheSlot& CarrierCacheSlot::operator=(const CarrierCacheSlot&) {
  cache = std::make_unique<CarrierCache>();
  return *this;
}

CarrierCache& carrier_cache(const PreparedModel& model) { return *model.carriers.cache; }

const CarrierField& CarrierCache::field(const PreparedModel& model, WaveletType wavelet, int threads) {
  const std::lock_guard lock(mutex_);
  auto& slot = fields_[wavelet];
  if (!slot) slot = std::make_unique<const CarrierField>(model, wavelet, threads);
  return *slot;
}

namespace {

// What a plan depends on besides the model: the key (as a digest), the length, the band rule.
std::string plan_name(const std::string& key, int payload_bits, const WatermarkOptions& options) {
  std::string name;
  for (const std::uint8_t byte : sha256(key)) name += static_cast<char>(byte);
  char rule[128];
  std::snprintf(rule, sizeof rule, "/%d/%d/%.17g/%.17g/%d", payload_bits, static_cast<int>(options.wavelet),
                options.min_support_vertices, options.min_carriers_per_bit, options.max_bands);
  return name + rule;
}

}  // namespace

std::shared_ptr<const SpreadPlan> CarrierCache::plan(const PreparedModel& model, const std::string& key,
                                                     int payload_bits, const WatermarkOptions& options, int threads) {
  const std::string name = plan_name(key, payload_bits, options);
  {
    const std::lock_guard lock(mutex_);
    for (auto it = plans_.begin(); it != plans_.end(); ++it)
      if (it->first == name) {
        plans_.splice(plans_.begin(), plans_, it);
        return plans_.front().second;
      }
  }
  // Built outside the lock: two readers of a new plan may both build it, and neither waits.
  auto made = std::make_shared<const SpreadPlan>(
      make_spread_plan(model, field(model, options.wavelet, threads), key, payload_bits, options));
  const std::lock_guard lock(mutex_);
  plans_.emplace_front(name, made);
  if (plans_.size() > kPlansKept) plans_.pop_back();
  return made;
}

std::shared_ptr<const Eigen::VectorXd> CarrierCache::pattern(const std::shared_ptr<const SpreadPlan>& plan,
                                                             const CarrierField& field, const Bits& codeword) {
  {
    const std::lock_guard lock(mutex_);
    for (auto it = patterns_.begin(); it != patterns_.end(); ++it)
      if (it->plan == plan && it->codeword == codeword) {
        patterns_.splice(patterns_.begin(), patterns_, it);
        return patterns_.front().field;
      }
  }
  auto made = std::make_shared<const Eigen::VectorXd>(
      field.to_vertices(plan_coefficients(*plan, signs_of(codeword), static_cast<int>(field.size()))));
  const std::lock_guard lock(mutex_);
  patterns_.push_front(Pattern{plan, codeword, made});
  if (patterns_.size() > kPatternsKept) patterns_.pop_back();
  return made;
}

}  // namespace meshmark
