#include "server/http/routes.hpp"

#include "server/http/handlers.hpp"

namespace meshmark::server {

namespace {

using Kind = BodyPlan::Kind;

std::vector<std::string> segments(const std::string& path) {
  std::vector<std::string> out;
  std::size_t start = 1;
  if (path.empty() || path[0] != '/') return {"\x01"};  // never matches
  while (start <= path.size()) {
    const std::size_t slash = path.find('/', start);
    out.push_back(path.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return out;
}

bool is_id(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  for (const char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return true;
}

bool matches(const std::string& pattern, const std::string& path, std::map<std::string, std::string>& params) {
  const auto want = segments(pattern), got = segments(path);
  if (want.size() != got.size()) return false;
  params.clear();
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (want[i] == "{id}") {
      if (!is_id(got[i])) return false;
      params["id"] = got[i];
    } else if (want[i] != got[i]) {
      return false;
    }
  }
  return true;
}

}  // namespace

const std::vector<Route>& api_routes() {
  static const std::vector<Route> routes = {
      {"POST", "/v1/owners", Access::admin, Kind::memory, handlers::create_owner},
      {"GET", "/v1/owners", Access::admin, Kind::none, handlers::list_owners},
      {"POST", "/v1/owners/{id}/key", Access::admin, Kind::memory, handlers::rotate_owner_key},
      {"DELETE", "/v1/owners/{id}/key", Access::admin, Kind::none, handlers::revoke_owner_key},
      {"GET", "/v1/owners/{id}/watermark-key", Access::admin, Kind::none, handlers::export_watermark_key},
      {"POST", "/v1/models", Access::owner, Kind::file, handlers::upload_model, handlers::check_upload},
      {"GET", "/v1/models", Access::owner, Kind::none, handlers::list_models},
      {"GET", "/v1/models/{id}", Access::owner, Kind::none, handlers::get_model},
      {"DELETE", "/v1/models/{id}", Access::owner, Kind::none, handlers::delete_model},
      {"GET", "/v1/models/{id}/embeddings", Access::owner, Kind::none, handlers::list_embeddings},
      {"GET", "/v1/models/{id}/detections", Access::owner, Kind::none, handlers::list_detections},
      {"GET", "/v1/models/{id}/copies.zip", Access::owner, Kind::none, handlers::download_copies},
      {"GET", "/v1/models/{id}/preview", Access::owner, Kind::none, handlers::model_preview},
      {"GET", "/v1/embeddings", Access::owner, Kind::none, handlers::export_embeddings},
      {"POST", "/v1/detect", Access::owner, Kind::file, handlers::detect_in_library, handlers::check_library_detect},
      {"POST", "/v1/models/{id}/embed", Access::owner, Kind::memory, handlers::embed, handlers::check_model_usable},
      {"POST", "/v1/models/{id}/detect", Access::owner, Kind::file, handlers::detect, handlers::check_detect},
      {"GET", "/v1/jobs/{id}", Access::owner, Kind::none, handlers::get_job},
      {"GET", "/v1/jobs/{id}/result", Access::owner, Kind::none, handlers::get_job_result},
      {"GET", "/v1/jobs/{id}/preview", Access::owner, Kind::none, handlers::job_preview},
      {"GET", "/v1/jobs/{id}/report", Access::owner, Kind::none, handlers::job_report},
      {"DELETE", "/v1/jobs/{id}", Access::owner, Kind::none, handlers::cancel_job},
      {"GET", "/livez", Access::anyone, Kind::none, handlers::livez, nullptr, true},
      {"GET", "/readyz", Access::anyone, Kind::none, handlers::readyz},
      {"GET", "/metrics", Access::anyone, Kind::none, handlers::metrics},
      {"GET", "/openapi.json", Access::anyone, Kind::none, handlers::openapi, nullptr, true},
  };
  return routes;
}

RouteMatch match_route(const std::string& method, const std::string& path) {
  RouteMatch match;
  std::map<std::string, std::string> params;
  for (const Route& r : api_routes()) {
    if (!matches(r.path, path, params)) continue;
    if (r.method == method) {
      match.route = &r;
      match.params = params;
      return match;
    }
    match.allowed += (match.allowed.empty() ? "" : ", ") + r.method;
  }
  return match;
}

std::string route_of(const std::string& method, const std::string& path) {
  const RouteMatch m = match_route(method, path);
  return m.route ? m.route->path : "other";
}

}  // namespace meshmark::server
