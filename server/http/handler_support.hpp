#pragma once
// What several handlers share: the caller, the request's JSON body and upload, the caller's
// models, places in the job queue, new job records.

#include <nlohmann/json.hpp>
#include <string>

#include "server/http/api.hpp"
#include "server/http/http_message.hpp"
#include "server/store/records.hpp"

namespace meshmark::server {

/// The owner admission authenticated.
const OwnerRecord& owner_of(const HttpRequest& req);

/// The body as a JSON object (400 when it is not JSON or nests deeper than 32 levels).
nlohmann::json json_body(const HttpRequest& req);

/// The bytes of an upload that was streamed to a file.
std::string upload_bytes(const HttpRequest& req);

/// The caller's model `id`; 404 when it does not exist for this owner.
ModelRecord owned_model(ApiContext& ctx, const OwnerRecord& owner, const std::string& id);
/// The caller's job of the request's {id}; 404 when it does not exist for this owner.
JobRecord owned_job(ApiContext& ctx, const HttpRequest& req);
/// The same, once it succeeded; 409 with its state (and error) before or otherwise.
JobRecord succeeded_job(ApiContext& ctx, const HttpRequest& req);

/// The model of the request's {id}, owned by its owner; 409 when it failed to prepare.
ModelRecord usable_model(ApiContext& ctx, const HttpRequest& req);

/// A place in the job queue for an owner (503 when the queue or the owner's share of it is full),
/// given back unless a job takes it.
class QueueSlot {
 public:
  QueueSlot(JobQueue& queue, std::string owner);
  ~QueueSlot();
  QueueSlot(const QueueSlot&) = delete;
  QueueSlot& operator=(const QueueSlot&) = delete;
  void push(const JobRecord& job);

 private:
  JobQueue& queue_;
  const std::string owner_;
  bool used_ = false;
};

/// A queued job asked to do `spec`, created now.
JobRecord new_job(const ApiContext& ctx, JobSpec spec, const OwnerRecord& owner, const std::string& model_id);

}  // namespace meshmark::server
