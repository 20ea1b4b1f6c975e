#include "proto/json_text.hpp"

namespace meshmark {

std::string json_text(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

namespace {

// Length of the UTF-8 sequence starting at text[i], or 0 if it is not a valid one; its code point
// in `decoded` when given.
std::size_t utf8_sequence(std::string_view text, std::size_t i, unsigned int* decoded = nullptr) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  std::size_t n = 0;
  unsigned int code = 0;
  if (c < 0x80) {
    if (decoded) *decoded = c;
    return 1;
  }
  if ((c & 0xE0) == 0xC0) n = 2, code = c & 0x1F;
  else if ((c & 0xF0) == 0xE0) n = 3, code = c & 0x0F;
  else if ((c & 0xF8) == 0xF0) n = 4, code = c & 0x07;
  else return 0;
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  const unsigned int smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < smallest[n] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;  // overlong, surrogate
  if (decoded) *decoded = code;
  return n;
}

// Controls (C0, DEL, C1) and the marks that reorder text around them (bidirectional overrides,
// embeddings, isolates): a name holding them can make a listing read as something else.
bool is_control_or_bidi(unsigned int code) {
  return code < 0x20 || (code >= 0x7F && code <= 0x9F) || code == 0x061C || code == 0x200E || code == 0x200F ||
         (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069);
}

}  // namespace

std::string clip_for_message(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return std::string(text);
  std::size_t end = 0;
  while (end < text.size()) {
    const std::size_t n = std::max<std::size_t>(1, utf8_sequence(text, end));
    if (end + n > max_bytes) break;
    end += n;
  }
  return std::string(text.substr(0, end)) + "\xE2\x80\xA6";
}

bool is_printable_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    unsigned int code = 0;
    const std::size_t n = utf8_sequence(text, i, &code);
    if (n == 0 || is_control_or_bidi(code)) return false;
    i += n;
  }
  return true;
}

std::string file_safe(std::string name) {
  for (char& c : name)
    if (c == '/' || c == '\\' || c == ':' || static_cast<unsigned char>(c) < 32) c = '_';
  return name;
}

}  // namespace meshmark
