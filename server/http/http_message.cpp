#include "server/http/http_message.hpp"

#include <strings.h>

namespace meshmark::server {

namespace {

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && ::strncasecmp(a.data(), b.data(), a.size()) == 0;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::string header_value(const HeaderList& headers, std::string_view name) {
  for (const auto& [n, v] : headers)
    if (same_name(n, name)) return v;
  return {};
}

std::size_t header_count(const HeaderList& headers, std::string_view name) {
  std::size_t count = 0;
  for (const auto& [n, v] : headers) count += same_name(n, name) ? 1 : 0;
  return count;
}

std::string HttpRequest::query_value(const std::string& name) const {
  const auto it = query.find(name);
  return it == query.end() ? std::string() : it->second;
}

std::optional<std::string> percent_decode(std::string_view text, bool plus_is_space) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '%') {
      if (i + 2 >= text.size()) return std::nullopt;
      const int hi = hex_digit(text[i + 1]), lo = hex_digit(text[i + 2]);
      if (hi < 0 || lo < 0) return std::nullopt;
      out += static_cast<char>(hi * 16 + lo);
      i += 2;
    } else {
      out += plus_is_space && c == '+' ? ' ' : c;
    }
  }
  return out;
}

bool split_target(std::string_view target, std::string& path, std::multimap<std::string, std::string>& query) {
  const std::size_t question = target.find('?');
  const auto decoded_path = percent_decode(target.substr(0, question), false);
  if (!decoded_path) return false;
  path = *decoded_path;
  query.clear();
  if (question == std::string_view::npos) return true;
  std::string_view rest = target.substr(question + 1);
  while (!rest.empty()) {
    const std::size_t amp = rest.find('&');
    const std::string_view pair = rest.substr(0, amp);
    rest = amp == std::string_view::npos ? std::string_view() : rest.substr(amp + 1);
    if (pair.empty()) continue;
    const std::size_t eq = pair.find('=');
    const auto name = percent_decode(pair.substr(0, eq), true);
    const auto value = percent_decode(eq == std::string_view::npos ? std::string_view() : pair.substr(eq + 1), true);
    if (!name || !value) return false;
    query.emplace(*name, *value);
  }
  return true;
}

}  // namespace meshmark::server
