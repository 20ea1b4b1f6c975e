#include "core/watermark/watermark_options.hpp"

#include <cstdio>

#include <stdexcept>

namespace meshmark {

std::string to_string(Scheme scheme) { return scheme == Scheme::paper ? "paper" : "spread"; }

Scheme parse_scheme(const std::string& name) {
  if (name == "spread") return Scheme::spread;
  if (name == "paper") return Scheme::paper;
  throw std::invalid_argument("unknown scheme '" + name + "' (expected spread or paper)");
}

std::string strength_range_text() {
  char text[96];
  std::snprintf(text, sizeof text, "[%g, %g] percent of the bounding-box diagonal", kMinStrengthPercent,
                kMaxStrengthPercent);
  return text;
}

}  // namespace meshmark
