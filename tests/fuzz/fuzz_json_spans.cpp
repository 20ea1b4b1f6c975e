// JsonSpans alone on arbitrary text: it refuses with MeshIoError or finds the root, whose span
// lies within the text and starts at its first non-blank byte; text that nlohmann::json accepts
// (within the depth limit, and without a NUL byte, where nlohmann stops reading as at the end)
// is never refused; nothing else escapes.

#include <nlohmann/json.hpp>

#include "core/io/json_spans.hpp"
#include "core/io/mesh_io_error.hpp"
#include "tests/fuzz/fuzz_target.hpp"

namespace {

// Deeper than JsonSpans' limit, counting brackets outside strings.
bool deeper_than(std::string_view text, int limit) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return true;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = as_text(data, size);
  constexpr int kDepth = 64;
  const bool valid =
      text.find('\0') == std::string_view::npos && nlohmann::json::accept(text) && !deeper_than(text, kDepth);
  try {
    const meshmark::JsonSpans spans(text, kDepth);
    const meshmark::ByteSpan root = spans.value("");
    const auto first = text.find_first_not_of(" \t\r\n");
    if (root.begin != first || root.end > text.size() || root.end <= root.begin) __builtin_trap();
  } catch (const meshmark::MeshIoError&) {
    if (valid) __builtin_trap();
  }
  return 0;
}
