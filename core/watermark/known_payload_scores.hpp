#pragma once
// The tail both schemes share: once a reading is chosen, the payloads known beforehand (the one
// expected, and every copy handed out) are each scored alone against it, with a p-value over the
// readings tried (and, for the copies, over how many there are).

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "core/watermark/watermark.hpp"

namespace meshmark {

/// ±1 per bit: 1 → +1, 0 → −1.
std::vector<double> signs_of(const Bits& bits);

/// The statistic of one sign pattern against a reading's per-carrier votes v (n):
/// Σ_k v_k · signs[bit_of[k]] / √norm2, with norm2 = ‖v‖² as the scheme computed it; 0 when norm2 is 0.
double vote_statistic(const Eigen::VectorXd& votes, const std::vector<int>& bit_of, const std::vector<double>& signs,
                      double norm2);

struct KnownPayloadScores {
  std::optional<double> expected_log10_p;  ///< options.expected's, over `tries` readings
  std::vector<double> candidate_log10_p;   ///< each of options.candidates', also over their number

  /// Sets the result's expected_(log10_)p_value and candidate_log10_p.
  void write_to(DetectResult& result) const;
};

/// `statistic(payload)`: the reading's statistic for that payload (e.g. vote_statistic of its signs).
KnownPayloadScores score_known_payloads(const DetectOptions& options, int tries,
                                        const std::function<double(const Bits&)>& statistic);

}  // namespace meshmark
