#pragma once
// The API's routes, in one table: what each answers with, who may call it and how its body is
// read. Metrics name requests by them, and tests check the table against the OpenAPI document
// in proto/ and against what the running daemon answers.

#include <map>
#include <string>
#include <vector>

#include "server/http/http_message.hpp"
#include "server/http/http_server.hpp"

namespace meshmark::server {

struct ApiContext;

/// Answers a request (its body read, its caller authenticated); throws ApiError to refuse.
using RouteHandler = HttpResponse (*)(ApiContext&, HttpRequest&);
/// Checks a request from its head alone, before the body is read; throws ApiError to refuse.
using RouteCheck = void (*)(ApiContext&, HttpRequest&);

enum class Access { anyone, owner, admin };

struct Route {
  std::string method;
  std::string path;  ///< OpenAPI form: /v1/models/{id}
  Access access = Access::owner;
  BodyPlan::Kind body = BodyPlan::Kind::none;  ///< memory: a JSON body; file: an upload
  RouteHandler handle = nullptr;
  RouteCheck check = nullptr;  ///< optional
  bool at_once = false;        ///< answered on an I/O thread: no store, no blocking
};

const std::vector<Route>& api_routes();

struct RouteMatch {
  const Route* route = nullptr;               ///< null: no route for this method and path
  std::map<std::string, std::string> params;  ///< {id} → the concrete segment
  std::string allowed;                        ///< the methods this path has, when the method is wrong ("GET, DELETE")
};

/// The route of a request. An {id} segment matches 1 to 64 letters, digits or '_'.
RouteMatch match_route(const std::string& method, const std::string& path);

/// The OpenAPI path of a concrete request path ("/v1/models/mdl_12" → "/v1/models/{id}"), for
/// metrics; "other" when it matches none.
std::string route_of(const std::string& method, const std::string& path);

}  // namespace meshmark::server
