#pragma once
// The API's handlers, one file per resource (owners, models, records, jobs, health); routes.cpp binds them
// to their routes. Each takes the context and the request and returns the response, or throws
// ApiError.

#include "server/http/http_message.hpp"

namespace meshmark::server {

struct ApiContext;

namespace handlers {

// owners_handlers.cpp
HttpResponse create_owner(ApiContext& ctx, HttpRequest& req);
HttpResponse list_owners(ApiContext& ctx, HttpRequest& req);
HttpResponse rotate_owner_key(ApiContext& ctx, HttpRequest& req);
HttpResponse revoke_owner_key(ApiContext& ctx, HttpRequest& req);
HttpResponse export_watermark_key(ApiContext& ctx, HttpRequest& req);

// models_handlers.cpp
void check_upload(ApiContext& ctx, HttpRequest& req);
HttpResponse upload_model(ApiContext& ctx, HttpRequest& req);
HttpResponse list_models(ApiContext& ctx, HttpRequest& req);
HttpResponse get_model(ApiContext& ctx, HttpRequest& req);
HttpResponse delete_model(ApiContext& ctx, HttpRequest& req);
HttpResponse list_embeddings(ApiContext& ctx, HttpRequest& req);
void check_model_usable(ApiContext& ctx, HttpRequest& req);
HttpResponse embed(ApiContext& ctx, HttpRequest& req);

// detect_handlers.cpp
void check_detect(ApiContext& ctx, HttpRequest& req);
HttpResponse detect(ApiContext& ctx, HttpRequest& req);
void check_library_detect(ApiContext& ctx, HttpRequest& req);
HttpResponse detect_in_library(ApiContext& ctx, HttpRequest& req);

// records_handlers.cpp
HttpResponse export_embeddings(ApiContext& ctx, HttpRequest& req);
HttpResponse list_detections(ApiContext& ctx, HttpRequest& req);
HttpResponse download_copies(ApiContext& ctx, HttpRequest& req);

// jobs_handlers.cpp
HttpResponse get_job(ApiContext& ctx, HttpRequest& req);
HttpResponse get_job_result(ApiContext& ctx, HttpRequest& req);
HttpResponse cancel_job(ApiContext& ctx, HttpRequest& req);

// view_handlers.cpp
HttpResponse model_preview(ApiContext& ctx, HttpRequest& req);
HttpResponse job_preview(ApiContext& ctx, HttpRequest& req);
HttpResponse job_report(ApiContext& ctx, HttpRequest& req);

// health_handlers.cpp
HttpResponse livez(ApiContext& ctx, HttpRequest& req);
HttpResponse readyz(ApiContext& ctx, HttpRequest& req);
HttpResponse metrics(ApiContext& ctx, HttpRequest& req);
HttpResponse openapi(ApiContext& ctx, HttpRequest& req);

}  // namespace handlers
}  // namespace meshmark::server
