#pragma once
// The spread scheme's carriers of one prepared model, built on first use and kept with it: the
// carrier field of each wavelet and the last few plans. Embedding a copy per recipient and
// reading each copy back then share one plan instead of each rebuilding it (the plan is most of
// a warm embed's time).

#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "core/watermark/carrier_field.hpp"
#include "core/watermark/payload_code.hpp"
#include "core/watermark/spread_plan.hpp"

namespace meshmark {

class CarrierCache {
 public:
  /// The field of `wavelet` on `model` (the cache's owner), built with `threads` on first use.
  const CarrierField& field(const PreparedModel& model, WaveletType wavelet, int threads);

  /// make_spread_plan's plan for these arguments; the key is kept only as a digest.
  std::shared_ptr<const SpreadPlan> plan(const PreparedModel& model, const std::string& key, int payload_bits,
                                         const WatermarkOptions& options, int threads);

  /// The field at the vertices of `plan`'s carriers signed by `codeword` (what embedding it adds,
  /// unscaled; `field` is the plan's): an embedding and the readings of its verification ask for
  /// the same one, so the last few are kept.
  std::shared_ptr<const Eigen::VectorXd> pattern(const std::shared_ptr<const SpreadPlan>& plan,
                                                 const CarrierField& field, const Bits& codeword);

  /// Plans kept (a model is marked by one owner's key, at one or two payload lengths).
  static constexpr std::size_t kPlansKept = 4;
  /// Patterns kept: those of the copies a few workers are making at once.
  static constexpr std::size_t kPatternsKept = 4;

 private:
  struct Pattern {
    std::shared_ptr<const SpreadPlan> plan;  // held, so that its address names it while kept
    Bits codeword;
    std::shared_ptr<const Eigen::VectorXd> field;
  };
  std::mutex mutex_;
  std::map<WaveletType, std::unique_ptr<const CarrierField>> fields_;
  std::list<std::pair<std::string, std::shared_ptr<const SpreadPlan>>> plans_;  // most recent first
  std::list<Pattern> patterns_;                                                 // most recent first
};

/// The cache of `model`'s carriers (PreparedModel::carriers).
CarrierCache& carrier_cache(const PreparedModel& model);

}  // namespace meshmark
