// GET /livez, /readyz, /metrics, /openapi.json: anyone.

#include "proto/openapi.hpp"
#include "server/http/api.hpp"
#include "server/http/api_error.hpp"
#include "server/http/handlers.hpp"
#include "server/http/problem.hpp"

namespace meshmark::server::handlers {

HttpResponse livez(ApiContext&, HttpRequest&) { return json_response(200, {{"status", "ok"}}); }

HttpResponse readyz(ApiContext& ctx, HttpRequest&) {
  if (ctx.draining.load()) return problem_response(503, "shutting down");
  if (!ctx.store.healthy()) return problem_response(503, "the store does not answer");
  const JobQueue::Counts counts = ctx.queue.counts();
  nlohmann::json body = {
      {"queued", counts.queued}, {"running", counts.running}, {"waiting_for_storage", counts.retrying}};
  if (counts.retrying > 0) {  // a problem document: its "status" is the HTTP status, never "ready"
    HttpResponse r = problem_response(503, "jobs wait for storage to accept their results (is the disk full?)", body);
    r.set_header("Retry-After", std::to_string(RetryAfter::not_ready));
    return r;
  }
  body["status"] = "ready";
  return json_response(200, body);
}

HttpResponse metrics(ApiContext& ctx, HttpRequest&) {
  const JobQueue::Counts counts = ctx.queue.counts();
  HttpResponse r;
  r.content_type = "text/plain; version=0.0.4";
  r.body = ctx.metrics.render(ctx.store.job_counts(), {.queued = counts.queued,
                                                       .running = counts.running,
                                                       .queue_capacity = ctx.queue.capacity(),
                                                       .memory_reserved = ctx.memory.reserved(),
                                                       .memory_ceiling = ctx.memory.ceiling(),
                                                       .instance = ctx.lease.owner});
  return r;
}

HttpResponse openapi(ApiContext&, HttpRequest&) {
  HttpResponse r;
  r.content_type = "application/json";
  r.body = openapi_document();
  return r;
}

}  // namespace meshmark::server::handlers
