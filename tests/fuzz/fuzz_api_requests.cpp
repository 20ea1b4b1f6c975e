// The daemon's request parsers on arbitrary JSON text, as the daemon feeds them: refused
// (std::invalid_argument) or parsed into values that read back the same.

#include <nlohmann/json.hpp>

#include "proto/api.hpp"
#include "proto/json_text.hpp"
#include "tests/fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = as_text(data, size);
  if (meshmark::json_nesting_depth(text) > 32) return 0;  // the daemon refuses these unparsed
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) return 0;
  try {
    const meshmark::EmbedRequest r = meshmark::parse_embed_request(j);
    const meshmark::EmbedRequest again = meshmark::parse_embed_request(meshmark::embed_request_json(r));
    if (again.payload != r.payload || again.recipient != r.recipient || again.format != r.format) __builtin_trap();
    (void)meshmark::json_text(meshmark::embed_request_json(r));
  } catch (const std::invalid_argument&) {
  }
  try {
    (void)meshmark::parse_owner_request(j);
  } catch (const std::invalid_argument&) {
  }
  if (j.is_object()) {
    try {
      (void)meshmark::parse_detect_query(j.value("scheme", ""), j.value("wavelet", ""), j.value("bits", ""));
    } catch (const std::invalid_argument&) {
    } catch (const nlohmann::json::exception&) {  // a key of another type: the daemon passes strings only
    }
  }
  return 0;
}
