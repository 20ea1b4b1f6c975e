#pragma once
// Base64 (RFC 4648, standard alphabet, padded), for glTF data URIs.

#include <optional>
#include <string>
#include <string_view>

namespace meshmark {

/// Decoded bytes, or nullopt when `text` is not base64.
std::optional<std::string> base64_decode(std::string_view text);
std::string base64_encode(std::string_view bytes);

}  // namespace meshmark
