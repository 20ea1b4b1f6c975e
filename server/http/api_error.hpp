#pragma once
// Errors a handler raises for the client to see, and the one function that turns any failure
// into an HTTP answer. Only ApiError's detail (and the core's complaints about the input) reach
// clients; everything else is logged and answered "internal error".

#include <exception>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "server/http/http_message.hpp"

namespace meshmark::server {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& detail, nlohmann::json extra = nlohmann::json::object())
      : std::runtime_error(detail), status_(status), extra_(std::move(extra)) {}
  int status() const noexcept { return status_; }
  const nlohmann::json& extra() const noexcept { return extra_; }

 private:
  int status_;
  nlohmann::json extra_;
};

/// The answer to a failure: ApiError with its status and detail; a full store 507; anything
/// else 500 "internal error", with the details in the log only.
HttpResponse error_response(std::exception_ptr error, const HttpRequest& request);

}  // namespace meshmark::server
