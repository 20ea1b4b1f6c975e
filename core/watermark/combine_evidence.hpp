#pragma once
// One detection decision from every test a detection made. Each test has an honest p-value of
// its own under "no watermark of this key" (unmarked mesh or wrong key; see docs/method.md, Decide):
//   blind decode    the decoder's best word among all 2^bits payloads (2^(bits+16) when its
//                   checksum fails: a word whose checksum matches is one of only 2^bits);
//   expected payload  the one payload the caller expects (`--expect`), scored alone;
//   known copy      the best of the recorded copies' payloads, charged for their number.
// The decision's p-value is the smallest of them times the number of tests made (Bonferroni:
// the chance that any of them is that small by accident is at most that), and the detection
// says which test decided. `detected` is p < false_alarm, so the fields cannot disagree.

#include "core/watermark/watermark.hpp"

namespace meshmark {

/// Reads r.blind_log10_p_value, r.expected_log10_p_value and r.candidate_log10_p (each already
/// charged for the readings and registrations tried); sets p_value, log10_p_value, evidence and
/// detected. `payload` (the decoded word) is kept only when it is what the evidence supports: a
/// checksum match, or the expected or known payload that decided.
void combine_evidence(DetectResult& r, const DetectOptions& options);

/// A detection chosen as the strongest of `readings` made with different settings (the daemon
/// reads each recorded copy with its own scheme, wavelet and payload length): its p-value times
/// their number, and `detected` decided again.
void charge_for_readings(DetectResult& r, int readings, double false_alarm);

}  // namespace meshmark
