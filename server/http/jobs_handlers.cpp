// /v1/jobs/{id}: a job's state, its result (the watermarked mesh of an embed job) and cancel.

#include "proto/json_text.hpp"
#include "server/clock.hpp"
#include "server/http/api_error.hpp"
#include "server/http/handler_support.hpp"
#include "server/http/handlers.hpp"
#include "server/http/problem.hpp"
#include "server/http/views.hpp"
#include "server/jobs/job_runner.hpp"
#include "server/store/blob_keys.hpp"

namespace meshmark::server::handlers {

namespace {

// Registered media types where there are (IANA: model/obj, model/stl, model/gltf-binary,
// model/gltf+json, model/3mf); PLY and OFF have none.
std::string media_type(const std::string& format) {
  if (format == "obj") return "model/obj";
  if (format == "stl") return "model/stl";
  if (format == "glb") return "model/gltf-binary";
  if (format == "gltf") return "model/gltf+json";
  if (format == "3mf") return "model/3mf";
  return "application/octet-stream";
}

}  // namespace

HttpResponse get_job(ApiContext& ctx, HttpRequest& req) { return json_response(200, job_view(owned_job(ctx, req))); }

HttpResponse get_job_result(ApiContext& ctx, HttpRequest& req) {
  const JobRecord job = succeeded_job(ctx, req);
  if (job.kind() != JobKind::embed) return json_response(200, job.result);
  const std::string format = job.result.value("format", "ply");
  const auto bytes = ctx.blobs.get(output_key(job.id, format));
  if (!bytes) throw NotFound("the watermarked mesh is no longer stored (its model was deleted?)");
  HttpResponse r;
  const bool zipped = job.result.value("zipped", false);
  r.content_type = zipped ? "application/zip" : media_type(format);
  r.body = *bytes;
  r.set_header("Content-Disposition",
               "attachment; filename=\"" + job.id + "." + format + (zipped ? ".zip" : "") + "\"");
  return r;
}

HttpResponse cancel_job(ApiContext& ctx, HttpRequest& req) {
  const OwnerRecord& owner = owner_of(req);
  const std::string& id = req.path_params.at("id");
  // The store decides, atomically; the queue then drops the job or signals its worker.
  const CancelOutcome outcome = ctx.store.cancel_job(owner.id, id);
  if (outcome == CancelOutcome::not_found) throw NotFound("no job '" + id + "'");
  const auto job = ctx.store.job(owner.id, id);
  if (!job) throw NotFound("no job '" + id + "'");  // its model was deleted meanwhile
  if (outcome == CancelOutcome::finished)
    throw Conflict("the job has already " + to_string(job->state), {{"state", to_string(job->state)}});
  ctx.queue.cancel(id);
  // Running: 202, it stops at its next check (or finishes first, if it was about to).
  return json_response(outcome == CancelOutcome::canceled ? 200 : 202, job_view(*job));
}

}  // namespace meshmark::server::handlers
