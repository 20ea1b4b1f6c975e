#pragma once
// Which of the copies handed out a suspect is. Every copy is read with the settings it was made
// with: copies that share (scheme, wavelet, payload length) are one reading, whose known-copy
// test covers them all, and the settings asked for are always read (their blind decode). The
// strongest reading decides, its p-value charged for the number of readings (combine_evidence);
// its copies are ranked by their own p-values, each charged for the copies it was read beside and
// for the readings, and the best is named when the detection decides and it is below the match
// threshold.

#include <optional>
#include <vector>

#include "core/watermark/watermark.hpp"

namespace meshmark {

/// One copy handed out: its payload (its length is the copy's payload length) and its settings.
struct KnownCopy {
  Bits payload;
  Scheme scheme = Scheme::spread;
  WaveletType wavelet = WaveletType::linear_lifting;
};

struct TraceOptions {
  /// The settings read even if no copy was made with them (when read_asked, or when there are no
  /// copies), and every other detection option (its `candidates` and `expected` are not used:
  /// the copies are the candidates).
  DetectOptions detect;
  /// Whether detect's own settings are read besides the copies' settings: false when they are
  /// only a default nobody asked for (a small model's copies carry shorter payloads than 64 bits,
  /// which the model could not even hold).
  bool read_asked = true;
  /// A copy is named when its own p-value is below 10^match_log10_p (and the detection decides).
  double match_log10_p = -6;
};

struct CopyScore {
  std::size_t copy = 0;      ///< index into the copies given
  double log10_p_value = 0;  ///< that copy's own test, charged for the copies and the readings
};

struct Tracing {
  DetectResult result;             ///< the reading that decided, charged for every reading
  std::size_t readings = 0;        ///< settings read
  std::vector<CopyScore> ranked;   ///< the deciding reading's copies, most likely first
  std::optional<CopyScore> match;  ///< the copy named, if any
};

/// `target` may be given to reuse the original's registration data. A paper-scheme reading is
/// skipped on a model that is not spherical. Throws what detect_watermark throws.
Tracing trace_copies(const PreparedModel& model, const Mesh& suspect, const std::string& key,
                     const std::vector<KnownCopy>& copies, const TraceOptions& options,
                     const RegistrationTarget* target = nullptr, const JobControl* control = nullptr);

}  // namespace meshmark
