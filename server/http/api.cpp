#include "server/http/api.hpp"

#include <spdlog/spdlog.h>

#include <set>
#include <string>

#include "proto/json_text.hpp"
#include "server/http/api_error.hpp"
#include "server/http/console_files.hpp"
#include "server/http/problem.hpp"
#include "server/http/routes.hpp"
#include "server/secrets.hpp"

namespace meshmark::server {

namespace {

std::string bearer_token(const HttpRequest& req) {
  const std::string header = req.header("Authorization");
  return header.rfind("Bearer ", 0) == 0 ? header.substr(7) : std::string();
}

void authorize(ApiContext& ctx, const Route& route, HttpRequest& req) {
  const std::string token = bearer_token(req);
  if (route.access == Access::admin) {
    if (token.empty() || !constant_time_equal(token, ctx.admin_token))
      throw Unauthorized("this needs the admin token: 'Authorization: Bearer <admin token>'");
  } else if (route.access == Access::owner) {
    if (token.empty()) throw Unauthorized("send your API key as 'Authorization: Bearer <key>'");
    auto owner = ctx.store.owner_by_key_hash(hash_api_key(token));
    if (!owner) throw Unauthorized("the API key is not valid");
    req.context = *owner;
  }
}

// The request's route, or the 404 / 405 answer.
std::variant<const Route*, HttpResponse> route_for(HttpRequest& req) {
  const RouteMatch match = match_route(req.method, req.path);
  if (match.route) {
    req.path_params = match.params;
    req.route = match.route->path;
    return match.route;
  }
  if (match.allowed.empty())
    return problem_response(404,
                            "no such endpoint: " + clip_for_message(req.method, 16) + " " + clip_for_message(req.path));
  HttpResponse r = problem_response(405, req.method + " is not served here; use " + match.allowed);
  r.set_header("Allow", match.allowed);
  return r;
}

std::size_t body_limit(const Route& route, const DaemonConfig& config) {
  switch (route.body) {
    case BodyPlan::Kind::memory:
      return kMaxJsonBodyBytes;
    case BodyPlan::Kind::file:
      return config.max_upload_bytes;
    case BodyPlan::Kind::none:
      return 0;
  }
  return 0;
}

// A file of the web console: static bytes, answered on the I/O thread.
std::optional<HttpResponse> console_response(HttpRequest& head) {
  if (head.method != "GET") return std::nullopt;
  const ConsoleFile* file = find_console_file(head.path);
  if (!file) return std::nullopt;
  head.route = "console";
  HttpResponse r;
  r.content_type = std::string(file->media_type);
  r.body = std::string(file->bytes);
  r.set_header("Content-Security-Policy", kConsoleContentSecurityPolicy);
  r.set_header("Referrer-Policy", "no-referrer");
  return r;
}

}  // namespace

std::optional<HttpResponse> ApiHandler::answer_at_once(HttpRequest& head) {
  if (auto console = console_response(head)) return console;
  const RouteMatch match = match_route(head.method, head.path);
  if (!match.route || !match.route->at_once) return std::nullopt;
  head.route = match.route->path;
  return match.route->handle(ctx_, head);
}

std::variant<HttpResponse, BodyPlan> ApiHandler::admit(HttpRequest& req) {
  auto found = route_for(req);
  if (auto* answer = std::get_if<HttpResponse>(&found)) return std::move(*answer);
  const Route& route = *std::get<const Route*>(found);
  try {
    authorize(ctx_, route, req);
    if (ctx_.draining.load() && req.method == "POST") {
      HttpResponse r = problem_response(503, "the daemon is shutting down; retry shortly");
      r.set_header("Retry-After", std::to_string(RetryAfter::draining));
      return r;
    }
    if (route.check) route.check(ctx_, req);
    BodyPlan plan;
    plan.kind = route.body;
    plan.limit = body_limit(route, ctx_.config);
    plan.length_required = route.body == BodyPlan::Kind::file;
    return plan;
  } catch (...) {
    return error_response(std::current_exception(), req);
  }
}

HttpResponse ApiHandler::respond(HttpRequest& req) {
  try {
    const RouteMatch match = match_route(req.method, req.path);
    return match.route->handle(ctx_, req);
  } catch (...) {
    return error_response(std::current_exception(), req);
  }
}

HttpResponse ApiHandler::refusal(int status, const std::string& detail) { return problem_response(status, detail); }

void ApiHandler::observe(const HttpRequest& req, const HttpResponse& res) {
  // Labels only from a fixed set: a client's bytes must not grow /metrics.
  static const std::set<std::string> methods = {"GET", "HEAD", "POST", "PUT", "PATCH", "DELETE", "OPTIONS"};
  ctx_.metrics.count_request(methods.count(req.method) ? req.method : "other", req.route.empty() ? "other" : req.route,
                             res.status);
  spdlog::debug("{} {} {}", clip_for_message(req.method, 16), clip_for_message(req.path), res.status);
}

}  // namespace meshmark::server
