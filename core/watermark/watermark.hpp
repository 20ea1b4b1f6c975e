#pragma once
// Embedding a keyed payload in a prepared model, and non-blind detection in a suspect mesh.
// The output of embedding has exactly the input's vertex order and faces; only positions move.

#include <algorithm>
#include <map>
#include <optional>
#include <string>

#include "core/registration/align_meshes.hpp"
#include "core/watermark/carrier_estimate.hpp"
#include "core/watermark/measure_by_projection.hpp"
#include "core/watermark/payload_code.hpp"
#include "core/util/job_control.hpp"
#include "core/watermark/prepared_model.hpp"
#include "core/watermark/watermark_options.hpp"

namespace meshmark {

struct EmbedResult {
  Mesh mesh;                        ///< the watermarked mesh
  int carriers = 0;                 ///< coefficients that carry the payload
  std::vector<int> carrier_levels;  ///< grid levels they live on
  int coded_bits = 0;
  double rms_displacement = 0;  ///< RMS over the surface of |v' − v| (linear per face), relative to the bbox diagonal
  double max_displacement = 0;  ///< relative to the bbox diagonal
  std::map<std::string, double> seconds;  ///< per stage
  /// What the user should know about this copy (e.g. a payload with little margin for the mesh).
  std::vector<std::string> warnings;
};

/// Embeds `payload` with `key`. Throws std::invalid_argument for an empty key or payload, or a
/// payload too long for the mesh; Canceled or TimeLimitExceeded when `control` says so.
EmbedResult embed_watermark(const PreparedModel& model, const std::string& key, const Bits& payload,
                            const WatermarkOptions& options = {}, const JobControl* control = nullptr);

/// How detection estimates the carriers from the measured field (carrier_estimate.hpp). Every
/// estimate tried is paid for in the false-alarm bound (bits_for_tries).
struct EstimateOptions {
  /// Relative regularizations μ/d of the spread scheme's estimates (0 = the matched filter;
  /// 1 suits heavy noise, 0.1 undoes the overlap of neighbouring carriers in light noise).
  std::vector<double> spread_regularizations{0.0, 1.0, 0.1};
  /// The paper scheme's (its carriers overlap less: a smaller μ suits it).
  std::vector<double> paper_regularizations{0.0, 1.0, 0.01};
  /// The paper scheme's when the suspect's vertices are the original's (vertex_offsets.hpp): its
  /// model is then exact up to the noise, and a near-converged solve with a tiny μ reads every
  /// carrier the embedding could place.
  std::vector<double> paper_vector_regularizations{0.0, 0.01, 1e-6};
  CarrierSolveOptions paper_vector_solve{200, 1e-16};
  /// The bound pays for at least this many estimates: a reading that tries only some of the
  /// detector's estimates (the matched filter first, see detect_watermark) decides as the whole
  /// detector would.
  std::size_t charged_estimates = 0;
  /// Read with the matched filter first and stop there when it decides (see detect_watermark). Off
  /// where the chosen estimate itself is measured: the paper's Table 1 rate is its best reading's.
  bool matched_first = true;
  /// What the false-alarm bound pays for, of `tried` estimates.
  std::size_t charged(std::size_t tried) const { return std::max(tried, charged_estimates); }
};

struct DetectOptions {
  WatermarkOptions watermark;  ///< the options the mesh was marked with
  int payload_bits = 64;
  std::optional<Bits> expected;  ///< the payload we expect: gives the bit error rate
  /// Payloads known to have been embedded (e.g. every copy handed out): each gets its own
  /// p-value, over this short list instead of every possible payload.
  std::vector<Bits> candidates;
  double false_alarm = 1e-6;  ///< detected when the p-value is below this
  AlignOptions align;
  DisplacementOptions displacement;
  EstimateOptions estimate;
};

struct DetectResult {
  bool detected = false;
  std::optional<Bits> payload;  ///< the decoded payload, when its checksum matches
  Bits decoded;                 ///< the decoder's best payload, checksum or not
  bool checksum_ok = false;
  /// The decision's p-value (combine_evidence.hpp): the chance that an unmarked mesh, or a wrong
  /// key, gives evidence this strong in any of the tests made. `detected` iff below false_alarm.
  double p_value = 1;
  double log10_p_value = 0;        ///< the same, where p_value underflows
  double blind_log10_p_value = 0;  ///< the blind decode's own test (no payload known)
  std::string evidence = "none";   ///< the test that decided: "blind decode", "expected payload", "known copy", "none"
  double z_score = 0;              ///< the detection statistic (a standard score under no watermark)
  double correlation = 0;          ///< normalized correlation of the measured and the decoded watermark
  std::optional<double> ber;       ///< against `expected`
  std::optional<double> expected_p_value;        ///< p-value of the expected payload alone
  std::optional<double> expected_log10_p_value;  ///< the same, where it underflows
  std::vector<double> candidate_log10_p;         ///< per candidate: log10 of its p-value (union over the list)
  Alignment alignment;                           ///< the registration read (the strongest of the candidates)
  std::size_t alignment_candidates = 1;          ///< registrations read (see align_candidates)
  std::size_t samples = 0;                       ///< points where the suspect was read
  std::size_t missing = 0;                       ///< of them, where it was not found (erasures)
  double raw_bit_error_rate = -1;                ///< paper scheme: share of carriers read wrongly (its Table 1 measure)
  std::map<std::string, double> seconds;
};

/// Detects in `suspect` (any triangle soup). `target` may be given to reuse the original's
/// registration data. Each registration is read with the matched filter first, its bound charged
/// for every estimate of `options.estimate`; the regularized estimates are tried only when that
/// reading does not decide (detected a million-fold below `false_alarm`, for what a caller may
/// charge later; its checksum matching; the payload `expected`). Throws std::invalid_argument for
/// bad options (empty key, no bits); Canceled or TimeLimitExceeded when `control` says so.
DetectResult detect_watermark(const PreparedModel& model, const Mesh& suspect, const std::string& key,
                              const DetectOptions& options = {}, const RegistrationTarget* target = nullptr,
                              const JobControl* control = nullptr);

/// Detects in `copy`, a mesh with the original's vertices in their order (a copy read back as
/// embed wrote it): its offset is read at each vertex along the original's normal, with no
/// registration and nothing missing; estimate, decoding and decision are detect_watermark's.
/// Throws std::invalid_argument as detect_watermark does, or when the vertex counts differ.
DetectResult detect_in_place(const PreparedModel& model, const Mesh& copy, const std::string& key,
                             const DetectOptions& options = {}, const JobControl* control = nullptr);

/// p-value bound for a statistic z over 2^bits candidate messages: min(1, 2^bits · e^{−z²/2}),
/// exact for sums of fixed weights with independent random signs (Hoeffding).
double false_alarm_bound(double z, int bits);
/// log10 of false_alarm_bound, without underflow.
double log10_false_alarm_bound(double z, int bits);

}  // namespace meshmark
