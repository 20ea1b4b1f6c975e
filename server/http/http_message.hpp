#pragma once
// An HTTP request and response as the API's handlers see them: plain values, independent of the
// transport that parsed them (server/http/http_server).

#include <any>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace meshmark::server {

using HeaderList = std::vector<std::pair<std::string, std::string>>;

/// The value of the first header called `name` (case-insensitive); empty when absent.
std::string header_value(const HeaderList& headers, std::string_view name);
/// How many headers are called `name` (case-insensitive).
std::size_t header_count(const HeaderList& headers, std::string_view name);

struct HttpRequest {
  std::string method;                             ///< "GET", "POST", ...
  std::string target;                             ///< as sent: "/v1/models?format=obj"
  std::string path;                               ///< percent-decoded; may hold any bytes (not necessarily UTF-8)
  std::multimap<std::string, std::string> query;  ///< percent-decoded names and values
  HeaderList headers;
  std::optional<std::uint64_t> content_length;
  bool keep_alive = true;

  std::string body;                 ///< bodies read into memory (JSON)
  std::filesystem::path body_file;  ///< bodies streamed to a file (uploads); removed after the response
  std::uint64_t body_bytes = 0;

  std::map<std::string, std::string> path_params;  ///< {id} of the matched route
  std::string route;                               ///< the matched route's template, for metrics
  std::any context;                                ///< what admission learned (the owner), for the handler

  std::string header(std::string_view name) const { return header_value(headers, name); }
  bool has_query(const std::string& name) const { return query.count(name) > 0; }
  /// The first value of a query parameter; empty when absent.
  std::string query_value(const std::string& name) const;
};

struct HttpResponse {
  int status = 200;
  std::string content_type;
  std::string body;
  HeaderList headers;

  void set_header(std::string name, std::string value) { headers.emplace_back(std::move(name), std::move(value)); }
};

/// Decodes %XX escapes (and '+' as a space when `plus_is_space`); nullopt for a malformed escape.
std::optional<std::string> percent_decode(std::string_view text, bool plus_is_space);

/// Splits a request target into its decoded path and query; false for malformed escapes.
bool split_target(std::string_view target, std::string& path, std::multimap<std::string, std::string>& query);

}  // namespace meshmark::server
