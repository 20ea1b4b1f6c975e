#pragma once
// The HTTP/JSON API under /v1 (see proto/openapi.json) as the transport's handler: routing,
// authentication, draining, and every failure turned into a problem response in one place.

#include <atomic>
#include <string>

#include "server/clock.hpp"
#include "server/config.hpp"
#include "server/http/http_server.hpp"
#include "server/jobs/job_queue.hpp"
#include "server/jobs/recover_jobs.hpp"
#include "server/memory_budget.hpp"
#include "server/metrics.hpp"
#include "server/model_cache.hpp"
#include "server/store/blob_store.hpp"
#include "server/store/store.hpp"

namespace meshmark::server {

struct ApiContext {
  Store& store;
  BlobStore& blobs;
  JobQueue& queue;
  ModelCache& models;
  MemoryBudget& memory;
  Metrics& metrics;
  const DaemonConfig& config;
  std::string admin_token;
  std::string master_key;  ///< what every owner's watermark key derives from (secrets.hpp)
  std::atomic<bool>& draining;
  const Clock& clock;
  const Lease& lease;  ///< what new jobs are held under
};

class ApiHandler : public HttpHandler {
 public:
  explicit ApiHandler(ApiContext& ctx) : ctx_(ctx) {}
  std::optional<HttpResponse> answer_at_once(HttpRequest& head) override;
  std::variant<HttpResponse, BodyPlan> admit(HttpRequest& req) override;
  HttpResponse respond(HttpRequest& request) override;
  HttpResponse refusal(int status, const std::string& detail) override;
  void observe(const HttpRequest& request, const HttpResponse& response) override;

 private:
  ApiContext& ctx_;
};

/// The largest JSON request body, in bytes.
inline constexpr std::size_t kMaxJsonBodyBytes = 64 * 1024;

}  // namespace meshmark::server
