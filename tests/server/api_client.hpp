#pragma once
// A small client of the daemon's HTTP API for integration tests: one connection per call, so
// it can be used from many threads at once.

#include <nlohmann/json.hpp>

#include <string>

#include "client/httplib.hpp"

namespace meshmark::test {

struct ApiResponse {
  int status = -1;  ///< -1: no answer
  std::string body;
  httplib::Headers headers;

  nlohmann::json json() const { return nlohmann::json::parse(body, nullptr, false); }
  std::string header(const std::string& name) const;
  bool is_problem() const;  ///< application/problem+json with a status and a detail
};

class ApiClient {
 public:
  ApiClient(int port, std::string token) : port_(port), token_(std::move(token)) {}

  ApiResponse get(const std::string& path) const;
  ApiResponse del(const std::string& path) const;
  ApiResponse post_json(const std::string& path, const nlohmann::json& body) const;
  ApiResponse post_bytes(const std::string& path, const std::string& bytes) const;

  /// Polls a job until it leaves queued/running (or `seconds` pass); returns its last view.
  nlohmann::json wait_job(const std::string& job_id, double seconds = 300) const;
  /// Creates an owner with the admin token; returns its API key.
  std::string create_owner(const std::string& admin_token, const std::string& name) const;
  /// Uploads a mesh file's bytes, waits until the model is prepared; returns the model view.
  nlohmann::json upload_ready(const std::string& bytes, const std::string& format, const std::string& name) const;

 private:
  httplib::Headers auth() const;
  int port_;
  std::string token_;
};

/// A file's bytes.
std::string file_bytes(const std::string& path);

/// A new owner `name` on the daemon at `port` with the creature uploaded and prepared (what most
/// daemon suites start from): its API key and the model's id.
struct OwnerWithModel {
  std::string key, model;
};
OwnerWithModel owner_with_creature(int port, const std::string& name);

}  // namespace meshmark::test
