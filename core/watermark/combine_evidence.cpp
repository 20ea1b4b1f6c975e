#include "core/watermark/combine_evidence.hpp"

#include <algorithm>
#include <cmath>

namespace meshmark {

void combine_evidence(DetectResult& r, const DetectOptions& options) {
  int tests = 1;
  double best = r.blind_log10_p_value;
  r.evidence = "blind decode";
  if (r.expected_log10_p_value) {
    ++tests;
    if (*r.expected_log10_p_value < best) best = *r.expected_log10_p_value, r.evidence = "expected payload";
  }
  if (!r.candidate_log10_p.empty()) {
    ++tests;
    const double closest = *std::min_element(r.candidate_log10_p.begin(), r.candidate_log10_p.end());
    if (closest < best) best = closest, r.evidence = "known copy";
  }
  r.log10_p_value = std::min(0.0, best + std::log10(static_cast<double>(tests)));
  r.p_value = std::pow(10.0, r.log10_p_value);
  r.detected = r.p_value < options.false_alarm;
  if (!r.detected) r.evidence = "none";
  if (r.evidence == "expected payload" && options.expected) r.payload = *options.expected;
}

void charge_for_readings(DetectResult& r, int readings, double false_alarm) {
  if (readings <= 1) return;
  r.log10_p_value = std::min(0.0, r.log10_p_value + std::log10(static_cast<double>(readings)));
  r.p_value = std::pow(10.0, r.log10_p_value);
  r.detected = r.p_value < false_alarm;
  if (!r.detected) r.evidence = "none";
}

}  // namespace meshmark
