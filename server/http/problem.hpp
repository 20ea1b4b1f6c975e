#pragma once
// RFC 9457 problem details: every error the API returns.

#include "server/http/httplib.hpp"

#include <nlohmann/json.hpp>
#include <string>

namespace meshmark::server {

/// Sets status, Content-Type application/problem+json and a body {type, title, status, detail, …extra}.
void problem(httplib::Response& res, int status, const std::string& detail, const nlohmann::json& extra = {});

/// A failure inside a handler that should become a problem response.
struct ApiError {
  int status;
  std::string detail;
  nlohmann::json extra = nlohmann::json::object();
};

}  // namespace meshmark::server
