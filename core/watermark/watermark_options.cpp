#include "core/watermark/watermark_options.hpp"

#include <stdexcept>

namespace meshmark {

std::string to_string(Scheme scheme) { return scheme == Scheme::paper ? "paper" : "spread"; }

Scheme parse_scheme(const std::string& name) {
  if (name == "spread") return Scheme::spread;
  if (name == "paper") return Scheme::paper;
  throw std::invalid_argument("unknown scheme '" + name + "' (expected spread or paper)");
}

}  // namespace meshmark
