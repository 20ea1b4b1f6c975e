#pragma once
// RFC 9457 problem details, the form of every error the API returns, and JSON responses.

#include <nlohmann/json.hpp>
#include <string>

#include "server/http/http_message.hpp"

namespace meshmark::server {

/// {type, title, status, detail, …extra} as application/problem+json.
HttpResponse problem_response(int status, const std::string& detail,
                              const nlohmann::json& extra = nlohmann::json::object());

/// `body` as application/json (invalid UTF-8 in strings replaced, never an exception).
HttpResponse json_response(int status, const nlohmann::json& body);

}  // namespace meshmark::server
