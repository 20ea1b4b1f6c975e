#pragma once
// Errors a handler raises for the client to see, one type per kind of refusal, and the one
// function that turns any failure into an HTTP answer (status, Retry-After). Only an ApiError's
// detail (and the core's complaints about the input) reach clients; everything else is logged
// and answered "internal error".

#include <exception>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "server/http/http_message.hpp"

namespace meshmark::server {

enum class ApiErrorKind {
  invalid_request,  ///< 400: a parameter or body the API does not accept
  unauthorized,     ///< 401: no key, or one that is not valid
  not_found,        ///< 404: no such resource (or not the caller's)
  conflict,         ///< 409: the resource is not in a state that allows this
  too_large,        ///< 413: more than the limits allow
  unprocessable,    ///< 422: a well-formed request whose mesh cannot be used
  unavailable,      ///< 503: the daemon cannot take it now; retry
};

/// The status code of each kind: the only place they are decided.
int http_status(ApiErrorKind kind);

class ApiError : public std::runtime_error {
 public:
  ApiError(ApiErrorKind kind, const std::string& detail, nlohmann::json extra = nlohmann::json::object())
      : std::runtime_error(detail), kind_(kind), extra_(std::move(extra)) {}
  ApiErrorKind kind() const noexcept { return kind_; }
  int status() const { return http_status(kind_); }
  const nlohmann::json& extra() const noexcept { return extra_; }

 private:
  ApiErrorKind kind_;
  nlohmann::json extra_;
};

#define MESHMARK_API_ERROR(Name, kind_value)                                                  \
  struct Name : ApiError {                                                                    \
    explicit Name(const std::string& detail, nlohmann::json extra = nlohmann::json::object()) \
        : ApiError(ApiErrorKind::kind_value, detail, std::move(extra)) {}                     \
  }
MESHMARK_API_ERROR(InvalidRequest, invalid_request);
MESHMARK_API_ERROR(Unauthorized, unauthorized);
MESHMARK_API_ERROR(NotFound, not_found);
MESHMARK_API_ERROR(Conflict, conflict);
MESHMARK_API_ERROR(TooLarge, too_large);
MESHMARK_API_ERROR(Unprocessable, unprocessable);
MESHMARK_API_ERROR(Unavailable, unavailable);
#undef MESHMARK_API_ERROR

/// Seconds a client is asked to wait (Retry-After) before trying again.
struct RetryAfter {
  static constexpr int unavailable = 5;    ///< an Unavailable error (the queue is full, ...)
  static constexpr int draining = 10;      ///< the daemon is shutting down
  static constexpr int storage_full = 30;  ///< the store refused a write for lack of space
  static constexpr int not_ready = 30;     ///< /readyz: the store does not answer
};

/// The answer to a failure: an ApiError with its kind's status and its detail; a full store
/// 507; anything else 500 "internal error", with the details in the log only.
HttpResponse error_response(std::exception_ptr error, const HttpRequest& request);

}  // namespace meshmark::server
