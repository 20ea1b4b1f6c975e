#include "server/http/api_error.hpp"

#include <spdlog/spdlog.h>

#include <utility>

#include "proto/json_text.hpp"
#include "server/http/problem.hpp"
#include "server/store/storage_error.hpp"

namespace meshmark::server {

int http_status(ApiErrorKind kind) {
  switch (kind) {
    case ApiErrorKind::invalid_request:
      return 400;
    case ApiErrorKind::unauthorized:
      return 401;
    case ApiErrorKind::not_found:
      return 404;
    case ApiErrorKind::conflict:
      return 409;
    case ApiErrorKind::too_large:
      return 413;
    case ApiErrorKind::unprocessable:
      return 422;
    case ApiErrorKind::unavailable:
      return 503;
  }
  return 500;
}

HttpResponse error_response(std::exception_ptr error, const HttpRequest& request) {
  const std::string where = clip_for_message(request.method + " " + request.path, 200);
  try {
    std::rethrow_exception(std::move(error));
  } catch (const ApiError& e) {
    HttpResponse r = problem_response(e.status(), e.what(), e.extra());
    if (e.kind() == ApiErrorKind::unavailable) r.set_header("Retry-After", std::to_string(RetryAfter::unavailable));
    return r;
  } catch (const StorageError& e) {
    spdlog::error("{}: storage: {}", where, e.what());
    switch (e.kind()) {
      case StorageError::Kind::full: {
        HttpResponse r = problem_response(507, "the server's storage is full; retry later");
        r.set_header("Retry-After", std::to_string(RetryAfter::storage_full));
        return r;
      }
      case StorageError::Kind::unavailable: {
        HttpResponse r = problem_response(503, "the server's storage did not answer; retry later");
        r.set_header("Retry-After", std::to_string(RetryAfter::unavailable));
        return r;
      }
      case StorageError::Kind::permanent:
        break;
    }
    return problem_response(500, "internal error");
  } catch (const std::exception& e) {
    spdlog::error("{}: {}", where, e.what());
  } catch (...) {
    spdlog::error("{}: unknown exception", where);
  }
  return problem_response(500, "internal error");
}

}  // namespace meshmark::server
