#pragma once
// Options shared by embedding and detection: detection must be given the same ones.

#include <string>

#include "core/wavelet/spherical_wavelet.hpp"

namespace meshmark {

enum class Scheme {
  spread,  ///< the default: coded payload spread by keyed chips over many carriers, along the normals
  paper,   ///< Jin et al.'s rule c' = c + g_j f(c) w, for reproducing their Table 1
};
std::string to_string(Scheme scheme);
Scheme parse_scheme(const std::string& name);  ///< "spread" or "paper"; throws std::invalid_argument

/// The strengths accepted, in percent of the bounding-box diagonal: [kMinStrengthPercent,
/// kMaxStrengthPercent]. Below the floor (1/50 of the default) a mark drowns in a format's own
/// rounding: a request for it is refused, not turned into a copy without a mark.
inline constexpr double kMinStrengthPercent = 0.001;
inline constexpr double kMaxStrengthPercent = 5;
/// True when `percent` is in that range (NaN is not).
inline bool strength_in_range(double percent) {
  return percent >= kMinStrengthPercent && percent <= kMaxStrengthPercent;
}
/// The range, for messages: "[0.001, 5] percent of the bounding-box diagonal".
std::string strength_range_text();

struct WatermarkOptions {
  Scheme scheme = Scheme::spread;
  WaveletType wavelet = WaveletType::linear_lifting;
  /// The distortion budget: RMS displacement of the surface (area-weighted over the vertices),
  /// in percent of the bounding-box diagonal. The measured MRMS comes out at or a little below.
  double strength_percent = 0.05;
  /// Spread scheme: a carrier band is used only if its basis functions cover at least this many
  /// mesh vertices on average (finer bumps do not survive simplification or remeshing)...
  double min_support_vertices = 10;
  /// ... and only if it has at least this many carriers per coded bit.
  double min_carriers_per_bit = 1;
  /// At most this many bands, the finest that qualify (0: all).
  int max_bands = 0;
};

}  // namespace meshmark
