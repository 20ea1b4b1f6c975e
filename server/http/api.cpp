#include "server/http/api.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"
#include "core/mesh/mesh_digest.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "core/watermark/payload_code.hpp"
#include "proto/api.hpp"
#include "proto/core_json.hpp"
#include "proto/openapi.hpp"
#include "server/clock.hpp"
#include "server/http/problem.hpp"
#include "server/http/routes.hpp"
#include "server/jobs/job_runner.hpp"
#include "server/secrets.hpp"

namespace meshmark::server {

namespace {

using httplib::Request;
using httplib::Response;

constexpr const char* kId = "([A-Za-z0-9_]{1,64})";

bool is_upload(const Request& req) {
  return req.method == "POST" && (req.path == "/v1/models" ||
                                   (req.path.rfind("/v1/models/", 0) == 0 && req.path.size() > 7 &&
                                    req.path.compare(req.path.size() - 7, 7, "/detect") == 0));
}

// Refuses bodies we cannot bound before a byte of them is read.
httplib::Server::HandlerResponse guard(const Request& req, Response& res, const ApiContext& ctx) {
  auto refuse = [&](int status, const std::string& detail) {
    problem(res, status, detail);
    res.set_header("Connection", "close");  // the unread body must not be taken for a request
    return httplib::Server::HandlerResponse::Handled;
  };
  if (req.has_header("Transfer-Encoding"))
    return refuse(411, "chunked or otherwise encoded transfers are refused; send the body with a Content-Length");
  if (req.has_header("Content-Encoding"))
    return refuse(415, "compressed request bodies are refused; send the body as it is");
  const bool has_length = req.has_header("Content-Length");
  if (!has_length && is_upload(req)) return refuse(411, "uploads need a Content-Length header");
  if (has_length) {
    const std::string value = req.get_header_value("Content-Length");
    std::size_t length = 0;
    try {
      std::size_t used = 0;
      length = std::stoull(value, &used);
      if (used != value.size()) throw std::invalid_argument("");
    } catch (const std::exception&) {
      return refuse(400, "Content-Length '" + value + "' is not a number");
    }
    if (length > ctx.config.max_upload_bytes)
      return refuse(413, "the body is " + std::to_string(length) + " bytes; the limit is " +
                             std::to_string(ctx.config.max_upload_bytes));
  }
  if (ctx.draining.load() && req.method == "POST") {
    res.set_header("Retry-After", "10");
    return refuse(503, "the daemon is shutting down; retry shortly");
  }
  return httplib::Server::HandlerResponse::Unhandled;
}

std::optional<OwnerRecord> authenticate(const Request& req, ApiContext& ctx) {
  const std::string header = req.get_header_value("Authorization");
  if (header.rfind("Bearer ", 0) != 0) throw ApiError{401, "send your API key as 'Authorization: Bearer <key>'"};
  auto owner = ctx.store.owner_by_key_hash(hash_api_key(header.substr(7)));
  if (!owner) throw ApiError{401, "the API key is not valid"};
  return owner;
}

nlohmann::json model_view(const ModelRecord& m) {
  nlohmann::json j = {{"id", m.id},
                      {"name", m.name},
                      {"format", m.format},
                      {"state", m.state},
                      {"vertices", m.vertices},
                      {"faces", m.faces},
                      {"digest", m.digest},
                      {"report", m.report},
                      {"created_at", m.created_at},
                      {"updated_at", m.updated_at},
                      {"links",
                       {{"self", "/v1/models/" + m.id},
                        {"embed", "/v1/models/" + m.id + "/embed"},
                        {"detect", "/v1/models/" + m.id + "/detect"},
                        {"embeddings", "/v1/models/" + m.id + "/embeddings"}}}};
  if (!m.error.empty()) j["error"] = m.error;
  return j;
}

nlohmann::json job_view(const JobRecord& j) {
  nlohmann::json v = {{"id", j.id},
                      {"kind", j.kind},
                      {"state", j.state},
                      {"progress", j.progress},
                      {"stage", j.stage},
                      {"attempts", j.attempts},
                      {"model_id", j.model_id},
                      {"created_at", j.created_at},
                      {"links", {{"self", "/v1/jobs/" + j.id}}}};
  if (!j.started_at.empty()) v["started_at"] = j.started_at;
  if (!j.finished_at.empty()) v["finished_at"] = j.finished_at;
  if (j.state == "succeeded") v["result"] = j.result;
  if (j.state == "failed" || j.state == "canceled") v["error"] = j.error;
  if (j.state == "succeeded" && j.kind == "embed") v["links"]["result"] = "/v1/jobs/" + j.id + "/result";
  return v;
}

void send_json(Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

// Streams the body to a temporary file under the byte cap, then returns its bytes.
std::string receive_upload(const httplib::ContentReader& reader, ApiContext& ctx) {
  const auto dir = ctx.config.data_dir / "uploads";
  std::filesystem::create_directories(dir);
  const auto path = dir / ("upload-" + random_hex(8));
  std::size_t total = 0;
  bool too_large = false, stored = true;
  std::ofstream out(path, std::ios::binary);
  const bool complete = reader([&](const char* data, std::size_t length) {
    total += length;
    if (total > ctx.config.max_upload_bytes) {
      too_large = true;
      return false;
    }
    out.write(data, static_cast<std::streamsize>(length));
    stored = static_cast<bool>(out);
    return stored;
  });
  out.close();
  stored = stored && static_cast<bool>(out);
  std::string bytes;
  if (complete && stored && !too_large) {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::filesystem::remove(path);
  if (too_large) throw ApiError{413, "the body exceeds the limit of " + std::to_string(ctx.config.max_upload_bytes) + " bytes"};
  if (!stored) throw ApiError{507, "the upload could not be stored (is the data directory full?)"};
  // A body cut short must never pass for a smaller mesh.
  if (!complete || bytes.size() != total)
    throw ApiError{400, "the body ended after " + std::to_string(total) + " bytes, before its Content-Length"};
  return bytes;
}

MeshFormat format_param(const Request& req) {
  const std::string name = req.get_param_value("format");
  if (name.empty()) throw ApiError{400, "say the mesh's format: ?format=obj, off, ply or stl"};
  const auto format = parse_mesh_format(name);
  if (!format) throw ApiError{400, "unknown format '" + name + "' (expected obj, off, ply or stl)"};
  return *format;
}

Mesh parse_upload(const std::string& bytes, MeshFormat format, ApiContext& ctx) {
  if (bytes.empty()) throw ApiError{400, "the body is empty; send the mesh file as the request body"};
  ReadOptions options;
  options.max_vertices = ctx.config.max_vertices;
  options.max_faces = 2 * ctx.config.max_vertices + 64;
  try {
    return read_mesh_from_memory(bytes, format, options, "the uploaded " + to_string(format) + " file").mesh;
  } catch (const MeshIoError& e) {
    const std::string what = e.what();
    throw ApiError{what.find("the limit for one mesh") != std::string::npos ? 413 : 400, what};
  }
}

// A place in the queue, given back unless a job takes it.
class QueueSlot {
 public:
  explicit QueueSlot(JobQueue& queue) : queue_(queue) {
    if (!queue_.reserve()) throw ApiError{503, "the job queue is full; retry later", {{"retry_after_seconds", 5}}};
  }
  ~QueueSlot() {
    if (!used_) queue_.release_reservation();
  }
  void push(const std::string& job_id) {
    queue_.push(job_id);
    used_ = true;
  }

 private:
  JobQueue& queue_;
  bool used_ = false;
};

JobRecord new_job(const std::string& kind, const OwnerRecord& owner, const std::string& model_id) {
  JobRecord j;
  j.id = new_id("job_");
  j.kind = kind;
  j.owner_id = owner.id;
  j.model_id = model_id;
  j.created_at = now_iso8601();
  j.stage = "queued";
  return j;
}

ModelRecord owned_model(ApiContext& ctx, const OwnerRecord& owner, const std::string& id) {
  auto m = ctx.store.model(owner.id, id);
  if (!m) throw ApiError{404, "no model '" + id + "'"};  // another owner's model does not exist for you
  return *m;
}

// Runs a handler, turning ApiError into problem responses.
template <typename Handler>
void handle(Response& res, Handler&& handler) {
  try {
    handler();
  } catch (const ApiError& e) {
    problem(res, e.status, e.detail, e.extra);
    if (e.status == 503) res.set_header("Retry-After", "5");
  }
}

void install_routes(httplib::Server& s, ApiContext& ctx) {
  s.Post("/v1/owners", [&](const Request& req, Response& res) {
    handle(res, [&] {
      const std::string header = req.get_header_value("Authorization");
      if (header.rfind("Bearer ", 0) != 0 || !constant_time_equal(header.substr(7), ctx.admin_token))
        throw ApiError{401, "creating owners needs the admin token: 'Authorization: Bearer <admin token>'"};
      nlohmann::json body = req.body.empty() ? nlohmann::json::object() : nlohmann::json::parse(req.body, nullptr, false);
      if (!body.is_object() || (body.contains("name") && !body["name"].is_string()))
        throw ApiError{400, "the body must be a JSON object with a string 'name', e.g. {\"name\": \"Studio A\"}"};
      OwnerRecord owner{new_id("own_"), body.value("name", std::string("owner")), now_iso8601()};
      const std::string key = new_api_key();
      ctx.store.insert_owner(owner, hash_api_key(key));
      res.set_header("Location", "/v1/owners/" + owner.id);
      send_json(res, 201, {{"owner_id", owner.id}, {"name", owner.name}, {"api_key", key}});
    });
  });

  s.Post("/v1/models", [&](const Request& req, Response& res, const httplib::ContentReader& reader) {
    handle(res, [&] {
      const OwnerRecord owner = *authenticate(req, ctx);
      const MeshFormat format = format_param(req);
      const Mesh mesh = parse_upload(receive_upload(reader, ctx), format, ctx);
      const MeshReport report = validate_mesh(mesh);
      if (!report.valid)
        throw ApiError{422, "the mesh cannot be watermarked: " + report.problems.front(), {{"report", report}}};
      QueueSlot slot(ctx.queue);
      ModelRecord m;
      m.id = new_id("mdl_");
      m.owner_id = owner.id;
      m.name = req.has_param("name") ? req.get_param_value("name") : "model";
      m.format = to_string(format);
      m.state = "preparing";
      m.report = report;
      m.vertices = static_cast<long long>(mesh.V.rows());
      m.faces = static_cast<long long>(mesh.F.rows());
      m.digest = mesh_digest(mesh);
      m.created_at = m.updated_at = now_iso8601();
      ctx.blobs.put(original_key(m.id), write_mesh_to_memory(mesh, MeshFormat::ply, {.binary = true}));
      JobRecord job = new_job("prepare", owner, m.id);
      ctx.store.insert_model(m, job);
      slot.push(job.id);
      nlohmann::json view = model_view(m);
      view["job_id"] = job.id;
      res.set_header("Location", "/v1/models/" + m.id);
      send_json(res, 202, view);
    });
  });

  s.Get("/v1/models", [&](const Request& req, Response& res) {
    handle(res, [&] {
      const OwnerRecord owner = *authenticate(req, ctx);
      nlohmann::json list = nlohmann::json::array();
      for (const auto& m : ctx.store.models(owner.id)) list.push_back(model_view(m));
      send_json(res, 200, {{"models", list}});
    });
  });

  s.Get(std::string("/v1/models/") + kId, [&](const Request& req, Response& res) {
    handle(res, [&] { send_json(res, 200, model_view(owned_model(ctx, *authenticate(req, ctx), req.matches[1]))); });
  });

  s.Delete(std::string("/v1/models/") + kId, [&](const Request& req, Response& res) {
    handle(res, [&] {
      const OwnerRecord owner = *authenticate(req, ctx);
      const std::string id = req.matches[1];
      if (!ctx.store.delete_model(owner.id, id)) throw ApiError{404, "no model '" + id + "'"};
      ctx.models.evict(id);
      ctx.blobs.remove_prefix("models/" + id);
      res.status = 204;
    });
  });

  s.Get(std::string("/v1/models/") + kId + "/embeddings", [&](const Request& req, Response& res) {
    handle(res, [&] {
      const ModelRecord m = owned_model(ctx, *authenticate(req, ctx), req.matches[1]);
      nlohmann::json list = nlohmann::json::array();
      for (const auto& e : ctx.store.embeddings(m.id))
        list.push_back({{"id", e.id}, {"payload", e.payload}, {"recipient", e.recipient}, {"job_id", e.job_id},
                        {"parameters", e.parameters}, {"created_at", e.created_at}});
      send_json(res, 200, {{"embeddings", list}});
    });
  });

  s.Post(std::string("/v1/models/") + kId + "/embed", [&](const Request& req, Response& res) {
    handle(res, [&] {
      const OwnerRecord owner = *authenticate(req, ctx);
      const ModelRecord m = owned_model(ctx, owner, req.matches[1]);
      if (m.state == "failed") throw ApiError{409, "the model failed to prepare: " + m.error};
      const nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
      EmbedRequest request;
      try {
        request = parse_embed_request(body);
      } catch (const std::invalid_argument& e) {
        throw ApiError{400, e.what()};
      }
      QueueSlot slot(ctx.queue);
      JobRecord job = new_job("embed", owner, m.id);
      EmbeddingRecord e{new_id("emb_"), m.id, owner.id, "", request.recipient, job.id, request.options, now_iso8601()};
      job.request = body;
      job.request["embedding_id"] = e.id;
      job.request["output_format"] = request.format.empty() ? m.format : request.format;
      auto record = [&](const std::string& payload) {
        e.payload = payload;
        job.request["assigned_payload"] = payload;
        return ctx.store.insert_embedding(e, job);
      };
      if (request.payload) {
        if (!record(*request.payload))
          throw ApiError{409, "this model already has a copy with payload " + *request.payload + "; see its embeddings"};
      } else {  // a fresh 64-bit payload, unique within the model
        bool stored = false;
        for (int attempt = 0; attempt < 16 && !stored; ++attempt) stored = record(random_hex(8));
        if (!stored) throw std::runtime_error("could not assign a unique payload");
      }
      slot.push(job.id);
      res.set_header("Location", "/v1/jobs/" + job.id);
      send_json(res, 202, {{"job_id", job.id}, {"embedding_id", e.id}, {"payload", e.payload},
                           {"recipient", e.recipient}, {"links", {{"job", "/v1/jobs/" + job.id}}}});
    });
  });

  s.Post(std::string("/v1/models/") + kId + "/detect",
         [&](const Request& req, Response& res, const httplib::ContentReader& reader) {
           handle(res, [&] {
             const OwnerRecord owner = *authenticate(req, ctx);
             const ModelRecord m = owned_model(ctx, owner, req.matches[1]);
             if (m.state == "failed") throw ApiError{409, "the model failed to prepare: " + m.error};
             const MeshFormat format = format_param(req);
             DetectRequest request;
             try {
               request = parse_detect_query(req.get_param_value("scheme"), req.get_param_value("wavelet"),
                                            req.get_param_value("bits"));
             } catch (const std::invalid_argument& e) {
               throw ApiError{400, e.what()};
             }
             const Mesh suspect = parse_upload(receive_upload(reader, ctx), format, ctx);
             QueueSlot slot(ctx.queue);
             JobRecord job = new_job("detect", owner, m.id);
             job.request = {{"scheme", to_string(request.options.scheme)},
                            {"wavelet", to_string(request.options.wavelet)},
                            {"bits", request.bits}};
             ctx.blobs.put(suspect_key(job.id), write_mesh_to_memory(suspect, MeshFormat::ply, {.binary = true}));
             ctx.store.insert_job(job);
             slot.push(job.id);
             res.set_header("Location", "/v1/jobs/" + job.id);
             send_json(res, 202, {{"job_id", job.id}, {"links", {{"job", "/v1/jobs/" + job.id}}}});
           });
         });

  s.Get(std::string("/v1/jobs/") + kId, [&](const Request& req, Response& res) {
    handle(res, [&] {
      const OwnerRecord owner = *authenticate(req, ctx);
      const auto job = ctx.store.job(owner.id, req.matches[1]);
      if (!job) throw ApiError{404, "no job '" + std::string(req.matches[1]) + "'"};
      send_json(res, 200, job_view(*job));
    });
  });

  s.Get(std::string("/v1/jobs/") + kId + "/result", [&](const Request& req, Response& res) {
    handle(res, [&] {
      const OwnerRecord owner = *authenticate(req, ctx);
      const auto job = ctx.store.job(owner.id, req.matches[1]);
      if (!job) throw ApiError{404, "no job '" + std::string(req.matches[1]) + "'"};
      if (job->state != "succeeded")
        throw ApiError{409, "the job is " + job->state + (job->error.empty() ? "" : ": " + job->error), {{"state", job->state}}};
      if (job->kind != "embed") return send_json(res, 200, job->result);
      const std::string format = job->result.value("format", "ply");
      const auto bytes = ctx.blobs.get(output_key(job->id, format));
      if (!bytes) throw ApiError{404, "the watermarked mesh is no longer stored (its model was deleted?)"};
      res.set_header("Content-Disposition", "attachment; filename=\"" + job->id + "." + format + "\"");
      res.set_content(*bytes, format == "obj" ? "model/obj" : format == "stl" ? "model/stl" : "application/octet-stream");
    });
  });

  s.Delete(std::string("/v1/jobs/") + kId, [&](const Request& req, Response& res) {
    handle(res, [&] {
      const OwnerRecord owner = *authenticate(req, ctx);
      const std::string id = req.matches[1];
      // The store decides, atomically; the queue then drops the job or signals its worker.
      const CancelOutcome outcome = ctx.store.cancel_job(owner.id, id, now_iso8601());
      if (outcome == CancelOutcome::not_found) throw ApiError{404, "no job '" + id + "'"};
      const auto job = ctx.store.job(owner.id, id);
      if (!job) throw ApiError{404, "no job '" + id + "'"};  // its model was deleted meanwhile
      if (outcome == CancelOutcome::finished)
        throw ApiError{409, "the job has already " + job->state, {{"state", job->state}}};
      ctx.queue.cancel(id);
      // Running: 202, it stops at its next checkpoint (or finishes first, if it was about to).
      send_json(res, outcome == CancelOutcome::canceled ? 200 : 202, job_view(*job));
    });
  });

  s.Get("/livez", [](const Request&, Response& res) { send_json(res, 200, {{"status", "ok"}}); });
  s.Get("/readyz", [&](const Request&, Response& res) {
    if (ctx.draining.load()) return problem(res, 503, "shutting down");
    if (!ctx.store.healthy()) return problem(res, 503, "the store does not answer");
    send_json(res, 200, {{"status", "ready"}, {"queued", ctx.queue.depth()}, {"running", ctx.queue.running()}});
  });
  s.Get("/metrics", [&](const Request&, Response& res) {
    res.set_content(ctx.metrics.render(ctx.store.job_counts(), ctx.queue.depth(), ctx.queue.running(), ctx.queue.capacity()),
                    "text/plain; version=0.0.4");
  });
  s.Get("/openapi.json", [](const Request&, Response& res) { res.set_content(openapi_document(), "application/json"); });
}

}  // namespace

void install_api(httplib::Server& server, ApiContext& ctx) {
  server.set_payload_max_length(ctx.config.max_upload_bytes);
  server.set_pre_routing_handler([&ctx](const Request& req, Response& res) { return guard(req, res, ctx); });
  install_routes(server, ctx);
  server.set_error_handler([](const Request& req, Response& res) {
    if (!res.body.empty()) return;
    problem(res, res.status, res.status == 404 ? "no such endpoint: " + req.method + " " + req.path : "request refused");
  });
  server.set_exception_handler([](const Request& req, Response& res, std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const std::exception& e) {
      spdlog::error("{} {}: {}", req.method, req.path, e.what());  // details stay in the log
    } catch (...) {
      spdlog::error("{} {}: unknown exception", req.method, req.path);
    }
    problem(res, 500, "internal error");
  });
  server.set_logger([&ctx](const Request& req, const Response& res) {
    ctx.metrics.count_request(req.method, route_of(req.method, req.path), res.status);
    spdlog::debug("{} {} {}", req.method, req.path, res.status);
  });
}

}  // namespace meshmark::server
