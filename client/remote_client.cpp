#include "client/remote_client.hpp"

#include "client/httplib.hpp"

#include <cctype>
#include <chrono>
#include <thread>

#include "proto/links.hpp"
#include "proto/states.hpp"

namespace meshmark::cli {

std::string encode_query_value(const std::string& text) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (const unsigned char c : text) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

namespace {

httplib::Headers headers_with(const std::string& token) {
  httplib::Headers h;
  if (!token.empty()) h.emplace("Authorization", "Bearer " + token);
  return h;
}

// What went wrong on the wire, in words (httplib names its errors in one word: "Connection").
std::string transport_problem(httplib::Error e) {
  switch (e) {
    case httplib::Error::Connection:
      return "nothing answers there (is meshmarkd running, and is --server right?)";
    case httplib::Error::ConnectionTimeout:
      return "the connection timed out";
    case httplib::Error::Read:
      return "the connection broke while reading the answer";
    case httplib::Error::Write:
      return "the connection broke while sending the request";
    case httplib::Error::SSLConnection:
      return "the TLS handshake failed";
    default:
      return "the request failed (" + httplib::to_string(e) + ")";
  }
}

// The body of a 2xx response, or a RemoteError with the problem's detail.
std::string checked(const httplib::Result& r, const std::string& what) {
  if (!r) throw RemoteError(0, "cannot reach the daemon for " + what + ": " + transport_problem(r.error()));
  if (r->status >= 200 && r->status < 300) return r->body;
  const auto j = nlohmann::json::parse(r->body, nullptr, false);
  const std::string detail = j.is_object() && j.contains("detail") ? j["detail"].get<std::string>() : r->body;
  throw RemoteError(r->status, what + ": " + std::to_string(r->status) + " " + detail);
}

}  // namespace

RemoteClient::RemoteClient(const std::string& server, std::string token) : token_(std::move(token)) {
  std::string rest = server;
  if (rest.rfind("http://", 0) == 0) rest = rest.substr(7);
  else if (rest.find("://") != std::string::npos)
    throw std::invalid_argument("only http:// servers are supported: " + server);
  while (!rest.empty() && rest.back() == '/') rest.pop_back();
  const auto colon = rest.rfind(':');
  host_ = colon == std::string::npos ? rest : rest.substr(0, colon);
  if (colon != std::string::npos) port_ = std::stoi(rest.substr(colon + 1));
}

nlohmann::json RemoteClient::get_json(const std::string& path) const {
  httplib::Client c(host_, port_);
  return nlohmann::json::parse(checked(c.Get(path, headers_with(token_)), "GET " + path));
}

nlohmann::json RemoteClient::post_json(const std::string& path, const nlohmann::json& body) const {
  httplib::Client c(host_, port_);
  return nlohmann::json::parse(
      checked(c.Post(path, headers_with(token_), body.dump(), "application/json"), "POST " + path));
}

nlohmann::json RemoteClient::post_file(const std::string& path, const std::string& bytes) const {
  httplib::Client c(host_, port_);
  c.set_read_timeout(300, 0);
  c.set_write_timeout(300, 0);
  return nlohmann::json::parse(
      checked(c.Post(path, headers_with(token_), bytes, "application/octet-stream"), "POST " + path));
}

void RemoteClient::remove(const std::string& path) const {
  httplib::Client c(host_, port_);
  checked(c.Delete(path, headers_with(token_)), "DELETE " + path);
}

std::string RemoteClient::get_bytes(const std::string& path) const {
  httplib::Client c(host_, port_);
  return checked(c.Get(path, headers_with(token_)), "GET " + path);
}

nlohmann::json RemoteClient::wait_job(const std::string& job_id,
                                      const std::function<void(const nlohmann::json& job)>& on_poll,
                                      int interval_ms) const {
  while (true) {
    nlohmann::json job = get_json(links::job(job_id));
    if (on_poll) on_poll(job);
    const auto state = parse_job_state(job.value("state", ""));
    if (!state)
      throw RemoteError(
          0, "the daemon answered job " + job_id + " with an unknown state '" + job.value("state", "") + "'");
    if (is_final(*state)) return job;
    std::this_thread::sleep_for(std::chrono::milliseconds(interval_ms));
  }
}

bool RemoteClient::alive() const {
  httplib::Client c(host_, port_);
  c.set_connection_timeout(2, 0);
  const auto r = c.Get("/livez");
  return r && r->status == 200;
}

}  // namespace meshmark::cli
