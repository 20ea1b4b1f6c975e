#include "server/http/problem.hpp"

#include "proto/json_text.hpp"

namespace meshmark::server {

namespace {

const char* title_of(int status) {
  switch (status) {
    case 400:
      return "Bad Request";
    case 401:
      return "Unauthorized";
    case 403:
      return "Forbidden";
    case 404:
      return "Not Found";
    case 405:
      return "Method Not Allowed";
    case 409:
      return "Conflict";
    case 411:
      return "Length Required";
    case 413:
      return "Content Too Large";
    case 415:
      return "Unsupported Media Type";
    case 417:
      return "Expectation Failed";
    case 422:
      return "Unprocessable Content";
    case 431:
      return "Request Header Fields Too Large";
    case 503:
      return "Service Unavailable";
    case 507:
      return "Insufficient Storage";
    default:
      return status >= 500 ? "Internal Server Error" : "Error";
  }
}

std::string slug_of(int status) {
  std::string slug;
  for (const char* c = title_of(status); *c; ++c) slug += *c == ' ' ? '-' : static_cast<char>(std::tolower(*c));
  return slug;
}

}  // namespace

HttpResponse problem_response(int status, const std::string& detail, const nlohmann::json& extra) {
  nlohmann::json body = {{"type", "https://meshmark.dev/problems/" + slug_of(status)},
                         {"title", title_of(status)},
                         {"status", status},
                         {"detail", detail}};
  if (extra.is_object())
    for (const auto& [k, v] : extra.items()) body[k] = v;
  HttpResponse r;
  r.status = status;
  r.content_type = "application/problem+json";
  r.body = json_text(body);
  return r;
}

HttpResponse json_response(int status, const nlohmann::json& body) {
  HttpResponse r;
  r.status = status;
  r.content_type = "application/json";
  r.body = json_text(body);
  return r;
}

}  // namespace meshmark::server
