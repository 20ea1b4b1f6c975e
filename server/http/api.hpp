#pragma once
// The HTTP/JSON API under /v1 (see proto/openapi.json), the health and metrics endpoints, and the
// guards every request passes first: body framing and size limits, authentication, draining.

#include "server/http/httplib.hpp"

#include <atomic>
#include <string>

#include "server/config.hpp"
#include "server/jobs/job_queue.hpp"
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
  Metrics& metrics;
  const DaemonConfig& config;
  std::string admin_token;
  std::atomic<bool>& draining;
};

/// Installs the routes, the pre-routing guard, the error and exception handlers and the access log.
void install_api(httplib::Server& server, ApiContext& context);

}  // namespace meshmark::server
