#include "server/http/api_error.hpp"

#include <spdlog/spdlog.h>

#include "proto/json_text.hpp"
#include "server/http/problem.hpp"
#include "server/store/storage_error.hpp"

namespace meshmark::server {

HttpResponse error_response(std::exception_ptr error, const HttpRequest& request) {
  const std::string where = clip_for_message(request.method + " " + request.path, 200);
  try {
    std::rethrow_exception(error);
  } catch (const ApiError& e) {
    HttpResponse r = problem_response(e.status(), e.what(), e.extra());
    if (e.status() == 503 || e.status() == 507) r.set_header("Retry-After", e.status() == 503 ? "5" : "30");
    return r;
  } catch (const StorageError& e) {
    spdlog::error("{}: storage: {}", where, e.what());
    if (!e.full()) return problem_response(500, "internal error");
    HttpResponse r = problem_response(507, "the server's storage is full; retry later");
    r.set_header("Retry-After", "30");
    return r;
  } catch (const std::exception& e) {
    spdlog::error("{}: {}", where, e.what());
  } catch (...) {
    spdlog::error("{}: unknown exception", where);
  }
  return problem_response(500, "internal error");
}

}  // namespace meshmark::server
