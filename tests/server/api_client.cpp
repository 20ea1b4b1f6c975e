#include "tests/server/api_client.hpp"

#include "tests/procedural_meshes.hpp"
#include "tests/server/daemon_process.hpp"

#include <chrono>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <thread>

namespace meshmark::test {

namespace {

httplib::Client connect(int port) {
  httplib::Client c("127.0.0.1", port);
  c.set_connection_timeout(10, 0);
  c.set_read_timeout(120, 0);
  c.set_write_timeout(120, 0);
  return c;
}

ApiResponse to_response(const httplib::Result& r) {
  ApiResponse out;
  if (!r) return out;
  out.status = r->status;
  out.body = r->body;
  out.headers = r->headers;
  return out;
}

}  // namespace

std::string ApiResponse::header(const std::string& name) const {
  const auto it = headers.find(name);
  return it == headers.end() ? "" : it->second;
}

bool ApiResponse::is_problem() const {
  const auto j = json();
  return header("Content-Type") == "application/problem+json" && j.is_object() && j.value("status", 0) == status &&
         j.contains("detail") && j["detail"].is_string() && !j["detail"].get<std::string>().empty();
}

httplib::Headers ApiClient::auth() const {
  if (token_.empty()) return {};
  return {{"Authorization", "Bearer " + token_}};
}

ApiResponse ApiClient::get(const std::string& path) const { return to_response(connect(port_).Get(path, auth())); }

ApiResponse ApiClient::del(const std::string& path) const { return to_response(connect(port_).Delete(path, auth())); }

ApiResponse ApiClient::post_json(const std::string& path, const nlohmann::json& body) const {
  return to_response(connect(port_).Post(path, auth(), body.dump(), "application/json"));
}

ApiResponse ApiClient::post_bytes(const std::string& path, const std::string& bytes) const {
  return to_response(connect(port_).Post(path, auth(), bytes, "application/octet-stream"));
}

nlohmann::json ApiClient::wait_job(const std::string& job_id, double seconds) const {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (true) {
    const ApiResponse r = get("/v1/jobs/" + job_id);
    if (r.status != 200) throw std::runtime_error("GET job " + job_id + ": " + std::to_string(r.status) + " " + r.body);
    const auto job = r.json();
    const std::string state = job.value("state", "");
    if ((state != "queued" && state != "running") || std::chrono::steady_clock::now() > deadline) return job;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

std::string ApiClient::create_owner(const std::string& admin_token, const std::string& name) const {
  ApiClient admin(port_, admin_token);
  const ApiResponse r = admin.post_json("/v1/owners", {{"name", name}});
  if (r.status != 201) throw std::runtime_error("create owner: " + std::to_string(r.status) + " " + r.body);
  return r.json().at("api_key").get<std::string>();
}

nlohmann::json ApiClient::upload_ready(const std::string& bytes, const std::string& format,
                                       const std::string& name) const {
  const ApiResponse r = post_bytes("/v1/models?format=" + format + "&name=" + name, bytes);
  if (r.status != 202) throw std::runtime_error("upload: " + std::to_string(r.status) + " " + r.body);
  const auto model = r.json();
  const auto job = wait_job(model.at("job_id").get<std::string>());
  if (job.value("state", "") != "succeeded") throw std::runtime_error("prepare: " + job.dump());
  return get("/v1/models/" + model.at("id").get<std::string>()).json();
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

OwnerWithModel owner_with_creature(int port, const std::string& name) {
  OwnerWithModel made;
  made.key = ApiClient(port, "").create_owner(DaemonProcess::admin_token(), name);
  made.model = ApiClient(port, made.key)
                   .upload_ready(file_bytes(procedural_file("creature")), "obj", "creature")
                   .at("id")
                   .get<std::string>();
  return made;
}

}  // namespace meshmark::test
