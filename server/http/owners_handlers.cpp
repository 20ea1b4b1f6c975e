// POST /v1/owners (admin): a new owner and its API key, shown once.

#include "proto/api.hpp"
#include "proto/links.hpp"
#include "server/clock.hpp"
#include "server/http/api_error.hpp"
#include "server/http/handler_support.hpp"
#include "server/http/handlers.hpp"
#include "server/http/problem.hpp"
#include "server/secrets.hpp"

namespace meshmark::server::handlers {

HttpResponse create_owner(ApiContext& ctx, HttpRequest& req) {
  OwnerRequest request;
  try {
    request = parse_owner_request(json_body(req));
  } catch (const std::invalid_argument& e) {
    throw ApiError(400, e.what());
  }
  OwnerRecord owner{new_id("own_"), request.name, now_iso8601()};
  const std::string key = new_api_key();
  ctx.store.insert_owner(owner, hash_api_key(key));
  HttpResponse r = json_response(201, {{"owner_id", owner.id}, {"name", owner.name}, {"api_key", key}});
  r.set_header("Location", links::owner(owner.id));
  return r;
}

}  // namespace meshmark::server::handlers
