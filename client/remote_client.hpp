#pragma once
// A small client of the meshmarkd API for the command line: JSON in and out, problem details
// turned into errors with their message.

#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace meshmark::cli {

/// A response the daemon refused; the message is the problem's detail.
class RemoteError : public std::runtime_error {
 public:
  RemoteError(int status, const std::string& detail) : std::runtime_error(detail), status(status) {}
  int status;
};

/// `text` percent-encoded for a URL query value (RFC 3986 unreserved characters kept).
std::string encode_query_value(const std::string& text);

class RemoteClient {
 public:
  /// `server`: "http://host:port"; `token`: an API key or the admin token (may be empty).
  RemoteClient(const std::string& server, std::string token);

  nlohmann::json get_json(const std::string& path) const;
  nlohmann::json post_json(const std::string& path, const nlohmann::json& body) const;
  nlohmann::json post_file(const std::string& path, const std::string& bytes) const;
  void remove(const std::string& path) const;
  /// The raw body of a GET (e.g. a mesh file).
  std::string get_bytes(const std::string& path) const;
  /// Polls a job until it finishes (every `interval_ms`), showing each view to `on_poll`;
  /// returns its final view.
  nlohmann::json wait_job(const std::string& job_id, const std::function<void(const nlohmann::json& job)>& on_poll = {},
                          int interval_ms = 200) const;
  /// GET /livez answered 200.
  bool alive() const;

 private:
  std::string host_;
  int port_ = 8080;
  std::string token_;
};

}  // namespace meshmark::cli
