#include "server/http/handler_support.hpp"

#include <fstream>
#include <iterator>

#include "proto/json_text.hpp"
#include "server/clock.hpp"
#include "server/http/api_error.hpp"
#include "server/jobs/recover_jobs.hpp"
#include "server/secrets.hpp"

namespace meshmark::server {

namespace {
constexpr std::size_t kMaxJsonDepth = 32;
}

const OwnerRecord& owner_of(const HttpRequest& req) {
  const auto* owner = std::any_cast<OwnerRecord>(&req.context);
  if (!owner) throw std::logic_error("a route that needs an owner was admitted without one");
  return *owner;
}

nlohmann::json json_body(const HttpRequest& req) {
  if (req.body.empty()) return nlohmann::json::object();
  if (json_nesting_depth(req.body) > kMaxJsonDepth)
    throw InvalidRequest("the JSON body nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
  if (body.is_discarded()) throw InvalidRequest("the body is not valid JSON");
  if (!body.is_object()) throw InvalidRequest("the body must be a JSON object");
  return body;
}

std::string upload_bytes(const HttpRequest& req) {
  std::ifstream in(req.body_file, std::ios::binary);
  std::string bytes(std::istreambuf_iterator<char>(in), {});
  if (!in.eof() && in.fail()) throw std::runtime_error("cannot read back the upload " + req.body_file.string());
  if (bytes.size() != req.body_bytes)
    throw std::runtime_error("the upload file " + req.body_file.string() + " changed size");
  return bytes;
}

ModelRecord owned_model(ApiContext& ctx, const OwnerRecord& owner, const std::string& id) {
  auto m = ctx.store.model(owner.id, id);
  if (!m) throw NotFound("no model '" + id + "'");  // another owner's model does not exist for you
  return *m;
}

JobRecord owned_job(ApiContext& ctx, const HttpRequest& req) {
  const std::string& id = req.path_params.at("id");
  auto job = ctx.store.job(owner_of(req).id, id);
  if (!job) throw NotFound("no job '" + id + "'");
  return *job;
}

JobRecord succeeded_job(ApiContext& ctx, const HttpRequest& req) {
  JobRecord job = owned_job(ctx, req);
  if (job.state != JobState::succeeded)
    throw Conflict("the job is " + to_string(job.state) + (job.error.empty() ? "" : ": " + job.error),
                   {{"state", to_string(job.state)}});
  return job;
}

ModelRecord usable_model(ApiContext& ctx, const HttpRequest& req) {
  ModelRecord m = owned_model(ctx, owner_of(req), req.path_params.at("id"));
  if (m.state == ModelState::failed) throw Conflict("the model failed to prepare: " + m.error);
  return m;
}

QueueSlot::QueueSlot(JobQueue& queue, std::string owner) : queue_(queue), owner_(std::move(owner)) {
  if (queue_.reserve(owner_)) return;
  if (queue_.held_by(owner_) >= queue_.owner_places())
    throw Unavailable("you have " + std::to_string(queue_.owner_places()) +
                          " jobs waiting, your share of the job queue; retry when some have run",
                      {{"retry_after_seconds", 5}});
  throw Unavailable("the job queue is full; retry later", {{"retry_after_seconds", 5}});
}

QueueSlot::~QueueSlot() {
  if (!used_) queue_.release_reservation(owner_);
}

void QueueSlot::push(const JobRecord& job) {
  queue_.push(queued_job(job));
  used_ = true;
}

JobRecord new_job(const ApiContext& ctx, JobSpec spec, const OwnerRecord& owner, const std::string& model_id) {
  JobRecord j;
  j.id = new_id("job_");
  j.spec = std::move(spec);
  j.owner_id = owner.id;
  j.model_id = model_id;
  j.created_at = ctx.clock.now_iso8601();
  j.lease_owner = ctx.lease.owner;
  j.lease_until = ctx.lease.until(ctx.clock);
  j.stage = to_string(JobState::queued);
  return j;
}

}  // namespace meshmark::server
