#include "core/watermark/detect_lengths.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "core/watermark/carrier_cache.hpp"
#include "core/watermark/combine_evidence.hpp"
#include "core/watermark/spread_plan.hpp"

namespace meshmark {

std::vector<int> plausible_payload_lengths(const PreparedModel& model, const WatermarkOptions& options, int threads) {
  if (options.scheme == Scheme::paper) return {64};
  const int capacity = payload_capacity_bits(carrier_cache(model).field(model, options.wavelet, threads), options);
  if (capacity >= 64) return {64};
  std::vector<int> lengths;
  for (const int bits : {16, 32})
    if (bits <= capacity) lengths.push_back(bits);
  if (capacity > 0 && (lengths.empty() || lengths.back() != capacity)) lengths.push_back(capacity);
  return lengths;
}

DetectResult detect_at_lengths(const PreparedModel& model, const Mesh& suspect, const std::string& key,
                               const std::vector<int>& lengths, DetectOptions options, const RegistrationTarget* target,
                               const JobControl* control) {
  if (lengths.empty()) throw std::invalid_argument("the mesh carries no payload with these settings");
  std::optional<RegistrationTarget> own;
  if (!target && lengths.size() > 1) target = &own.emplace(model.outward_mesh());  // shared by the readings
  std::optional<DetectResult> best;
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    options.payload_bits = lengths[i];
    const double n = static_cast<double>(lengths.size());
    std::optional<JobControl> part;
    if (control) part = rescaled(*control, 0.0, 1.0, i / n, (i + 1) / n);
    DetectResult r = detect_watermark(model, suspect, key, options, target, part ? &*part : nullptr);
    const bool better =
        !best || (r.checksum_ok != best->checksum_ok ? r.checksum_ok : r.log10_p_value < best->log10_p_value);
    if (better) best = std::move(r);
  }
  charge_for_readings(*best, static_cast<int>(lengths.size()), options.false_alarm);
  return *best;
}

}  // namespace meshmark
