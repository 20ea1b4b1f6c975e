// The owners (admin only): POST /v1/owners makes one and its API key, shown once; GET lists
// them; POST /v1/owners/{id}/key rotates the key (a new one, shown once; the old one stops
// working at once) and DELETE revokes it (no key works until the next rotation); GET
// /v1/owners/{id}/watermark-key gives the key its copies are marked under, for the local CLI.

#include <algorithm>

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
    throw InvalidRequest(e.what());
  }
  for (const OwnerRecord& o : ctx.store.owners())  // one name, one owner: a second "studio" is a mistake
    if (o.name == request.name)
      throw Conflict("an owner named '" + request.name + "' exists (" + o.id +
                         "); give another name, or rotate that owner's key if it was lost",
                     {{"owner_id", o.id}});
  OwnerRecord owner{new_id("own_"), request.name, ctx.clock.now_iso8601()};
  const std::string key = new_api_key();
  ctx.store.insert_owner(owner, hash_api_key(key));
  HttpResponse r = json_response(201, {{"owner_id", owner.id}, {"name", owner.name}, {"api_key", key}});
  r.set_header("Location", links::owner(owner.id));
  return r;
}

HttpResponse list_owners(ApiContext& ctx, HttpRequest&) {
  nlohmann::json list = nlohmann::json::array();
  for (const OwnerRecord& o : ctx.store.owners())
    list.push_back({{"owner_id", o.id}, {"name", o.name}, {"created_at", o.created_at}, {"key_active", o.key_active}});
  return json_response(200, {{"owners", list}});
}

HttpResponse rotate_owner_key(ApiContext& ctx, HttpRequest& req) {
  const std::string& id = req.path_params.at("id");
  const std::string key = new_api_key();
  if (!ctx.store.set_api_key(id, hash_api_key(key))) throw NotFound("no owner " + id);
  return json_response(200, {{"owner_id", id}, {"api_key", key}});
}

HttpResponse revoke_owner_key(ApiContext& ctx, HttpRequest& req) {
  const std::string& id = req.path_params.at("id");
  if (!ctx.store.set_api_key(id, "")) throw NotFound("no owner " + id);
  HttpResponse r;
  r.status = 204;
  return r;
}

HttpResponse export_watermark_key(ApiContext& ctx, HttpRequest& req) {
  const std::string& id = req.path_params.at("id");
  const auto owners = ctx.store.owners();
  if (std::none_of(owners.begin(), owners.end(), [&](const OwnerRecord& o) { return o.id == id; }))
    throw NotFound("no owner " + id);
  return json_response(200, {{"owner_id", id}, {"watermark_key", owner_watermark_key(ctx.master_key, id)}});
}

}  // namespace meshmark::server::handlers
