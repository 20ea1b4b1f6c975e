#pragma once
// The key and payload both end-to-end suites mark with, and how they detect with them.

#include <string>

#include "core/watermark/watermark.hpp"

namespace meshmark::test {

inline const std::string kEndToEndKey = "studio secret 42";

inline const Bits& end_to_end_payload() {
  static const Bits p = bits_from_hex("c0ffee15deadbeef");
  return p;
}

/// Detection of `suspect` against a prepared model, expecting the end-to-end payload.
inline DetectResult detect_end_to_end(const PreparedModel& model, const RegistrationTarget& target, const Mesh& suspect,
                                      const std::string& key = kEndToEndKey) {
  DetectOptions options;
  options.expected = end_to_end_payload();
  return detect_watermark(model, suspect, key, options, &target);
}

}  // namespace meshmark::test
