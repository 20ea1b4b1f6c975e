#pragma once
// JSON as text, safely: strings from users or files may hold bytes that are not UTF-8, and
// nlohmann::json::dump() throws on them. Everything the daemon and the CLI serialize goes
// through here.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/util/json_nesting_depth.hpp"

namespace meshmark {

/// Compact JSON text of `j`; invalid UTF-8 in strings becomes U+FFFD. Never throws on content.
std::string json_text(const nlohmann::json& j, int indent = -1);

/// `text` cut to at most `max_bytes` (at a UTF-8 character boundary), with "…" when cut:
/// for echoing user input in messages.
std::string clip_for_message(std::string_view text, std::size_t max_bytes = 120);

/// True when `text` is valid UTF-8 without control characters or bidirectional formatting marks
/// (names, labels: what a listing shows must read as what it is).
bool is_printable_utf8(std::string_view text);

/// `name` with what a file name cannot hold ('/', '\\', ':', control characters) replaced by '_':
/// for the files copies are saved as, named after their model and recipient.
std::string file_safe(std::string name);

}  // namespace meshmark
