#pragma once
// The API's routes, in one table: metrics name requests by them, and tests check the table
// against the OpenAPI document in proto/ and against what the running daemon answers.

#include <string>
#include <vector>

namespace meshmark::server {

struct RouteSpec {
  std::string method;
  std::string path;  ///< OpenAPI form: /v1/models/{id}
};

const std::vector<RouteSpec>& api_routes();

/// The OpenAPI path of a concrete request path ("/v1/models/mdl_12" → "/v1/models/{id}"), for
/// metrics; "other" when it matches none.
std::string route_of(const std::string& method, const std::string& path);

}  // namespace meshmark::server
