#include "core/watermark/trace_copies.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include "core/watermark/combine_evidence.hpp"

namespace meshmark {

namespace {

// Scheme and wavelet by name, then payload bits: readings run in this order (a tie keeps the first).
using Settings = std::tuple<std::string, std::string, int>;

// Copy indices grouped by the settings they were made with; the asked settings present when
// read_asked or when there are no copies.
std::map<Settings, std::vector<std::size_t>> group_by_settings(const std::vector<KnownCopy>& copies,
                                                               const TraceOptions& options) {
  std::map<Settings, std::vector<std::size_t>> groups;
  const DetectOptions& asked = options.detect;
  if (options.read_asked || copies.empty())
    groups[Settings{to_string(asked.watermark.scheme), to_string(asked.watermark.wavelet), asked.payload_bits}] = {};
  for (std::size_t i = 0; i < copies.size(); ++i)
    groups[Settings{to_string(copies[i].scheme), to_string(copies[i].wavelet),
                    static_cast<int>(copies[i].payload.size())}]
        .push_back(i);
  return groups;
}

// The deciding reading's copies, each p-value also charged for the readings made (the copies of
// every reading were candidates), most likely first.
std::vector<CopyScore> rank_copies(const DetectResult& r, const std::vector<std::size_t>& copies,
                                   std::size_t readings) {
  const double charge = std::log10(static_cast<double>(std::max<std::size_t>(readings, 1)));
  std::vector<CopyScore> ranked;
  for (std::size_t k = 0; k < copies.size(); ++k)
    ranked.push_back({copies[k], std::min(0.0, r.candidate_log10_p[k] + charge)});
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const CopyScore& a, const CopyScore& b) { return a.log10_p_value < b.log10_p_value; });
  return ranked;
}

}  // namespace

Tracing trace_copies(const PreparedModel& model, const Mesh& suspect, const std::string& key,
                     const std::vector<KnownCopy>& copies, const TraceOptions& options,
                     const RegistrationTarget* target, const JobControl* control) {
  const auto groups = group_by_settings(copies, options);
  std::optional<DetectResult> best;
  const std::vector<std::size_t>* deciding = nullptr;
  for (const auto& [settings, members] : groups) {
    DetectOptions reading = options.detect;
    reading.watermark.scheme = parse_scheme(std::get<0>(settings));
    reading.watermark.wavelet = parse_wavelet_type(std::get<1>(settings));
    reading.payload_bits = std::get<2>(settings);
    if (reading.watermark.scheme == Scheme::paper && !model.spherical()) continue;
    reading.expected.reset();
    reading.candidates.clear();
    for (std::size_t i : members) reading.candidates.push_back(copies[i].payload);
    DetectResult r = detect_watermark(model, suspect, key, reading, target, control);
    if (!best || r.log10_p_value < best->log10_p_value) best = std::move(r), deciding = &members;
  }
  if (!best) throw std::invalid_argument("no reading applies to this model");
  Tracing tracing;
  tracing.readings = groups.size();
  charge_for_readings(*best, static_cast<int>(groups.size()), options.detect.false_alarm);
  tracing.ranked = rank_copies(*best, *deciding, groups.size());
  if (best->detected && !tracing.ranked.empty() && tracing.ranked.front().log10_p_value < options.match_log10_p)
    tracing.match = tracing.ranked.front();
  tracing.result = std::move(*best);
  return tracing;
}

}  // namespace meshmark
