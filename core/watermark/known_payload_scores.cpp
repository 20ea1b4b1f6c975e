#include "core/watermark/known_payload_scores.hpp"

#include <cmath>

#include "core/watermark/carrier_estimate.hpp"

namespace meshmark {

std::vector<double> signs_of(const Bits& bits) {
  std::vector<double> s(bits.size());
  for (std::size_t i = 0; i < bits.size(); ++i) s[i] = bits[i] ? 1.0 : -1.0;
  return s;
}

double vote_statistic(const Eigen::VectorXd& votes, const std::vector<int>& bit_of, const std::vector<double>& signs,
                      double norm2) {
  double sum = 0;
  for (Eigen::Index k = 0; k < votes.size(); ++k) sum += votes[k] * signs[static_cast<std::size_t>(bit_of[k])];
  return norm2 > 0 ? sum / std::sqrt(norm2) : 0.0;
}

void KnownPayloadScores::write_to(DetectResult& result) const {
  result.expected_log10_p_value = expected_log10_p;
  if (expected_log10_p) result.expected_p_value = std::pow(10.0, *expected_log10_p);
  result.candidate_log10_p = candidate_log10_p;
}

KnownPayloadScores score_known_payloads(const DetectOptions& options, int tries,
                                        const std::function<double(const Bits&)>& statistic) {
  KnownPayloadScores scores;
  if (options.expected) scores.expected_log10_p = log10_false_alarm_bound(statistic(*options.expected), tries);
  const int list_bits = bits_for_tries(options.candidates.size());
  for (const Bits& candidate : options.candidates)
    scores.candidate_log10_p.push_back(log10_false_alarm_bound(statistic(candidate), tries + list_bits));
  return scores;
}

}  // namespace meshmark
