#include "server/http/routes.hpp"

#include <regex>

namespace meshmark::server {

const std::vector<RouteSpec>& api_routes() {
  static const std::vector<RouteSpec> routes = {
      {"POST", "/v1/owners"},
      {"POST", "/v1/models"},
      {"GET", "/v1/models"},
      {"GET", "/v1/models/{id}"},
      {"DELETE", "/v1/models/{id}"},
      {"GET", "/v1/models/{id}/embeddings"},
      {"POST", "/v1/models/{id}/embed"},
      {"POST", "/v1/models/{id}/detect"},
      {"GET", "/v1/jobs/{id}"},
      {"GET", "/v1/jobs/{id}/result"},
      {"DELETE", "/v1/jobs/{id}"},
      {"GET", "/livez"},
      {"GET", "/readyz"},
      {"GET", "/metrics"},
      {"GET", "/openapi.json"},
  };
  return routes;
}

std::string route_of(const std::string& method, const std::string& path) {
  static const std::regex id_segment(R"(/(v1/(?:models|jobs))/[^/]+)");
  const std::string templated = std::regex_replace(path, id_segment, "/$1/{id}");
  for (const RouteSpec& r : api_routes())
    if (r.method == method && r.path == templated) return templated;
  return "other";
}

}  // namespace meshmark::server
