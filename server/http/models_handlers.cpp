// /v1/models: upload an original, list, read and delete models, list their copies, and queue
// embed and detect jobs on them.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <deque>

#include "core/io/document_surface.hpp"
#include "core/io/packaged_document.hpp"
#include "core/io/write_mesh.hpp"
#include "core/mesh/mesh_digest.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "core/registration/shape_signature.hpp"
#include "core/watermark/spread_plan.hpp"
#include "core/util/job_control.hpp"
#include "proto/api.hpp"
#include "proto/core_json.hpp"
#include "proto/json_text.hpp"
#include "proto/links.hpp"
#include "server/clock.hpp"
#include "server/http/api_error.hpp"
#include "server/http/handler_support.hpp"
#include "server/http/handlers.hpp"
#include "server/http/problem.hpp"
#include "server/http/upload_parsing.hpp"
#include "server/http/views.hpp"
#include "server/jobs/job_runner.hpp"
#include "server/memory_budget.hpp"
#include "server/model_cache.hpp"
#include "server/secrets.hpp"
#include "server/store/blob_keys.hpp"

namespace meshmark::server::handlers {

void check_upload(ApiContext&, HttpRequest& req) {
  format_param(req);
  name_param(req);
}

HttpResponse upload_model(ApiContext& ctx, HttpRequest& req) {
  const OwnerRecord& owner = owner_of(req);
  const MeshFormat format = format_param(req);
  const ParsedUpload upload = parse_upload(req, format, ctx);
  const PackagedDocument& document = upload.document;
  const WeldedSurface surface = document_surface(document.document());
  const Mesh& mesh = surface.mesh;
  const MeshReport report = validate_mesh(mesh);
  if (!report.valid)
    throw Unprocessable("the mesh cannot be watermarked: " + report.problems.front(), {{"report", report}});
  QueueSlot slot(ctx.queue, owner.id);
  ModelRecord m;
  m.id = new_id("mdl_");
  m.owner_id = owner.id;
  m.name = name_param(req);
  m.format = to_string(format);
  m.state = ModelState::preparing;
  m.report = report;
  m.vertices = static_cast<long long>(mesh.V.rows());
  m.faces = static_cast<long long>(mesh.F.rows());
  m.digest = mesh_digest(mesh);
  m.report[kShapeSignatureKey] = signature_values(shape_signature(mesh));  // what a library search compares
  m.created_at = m.updated_at = ctx.clock.now_iso8601();
  ctx.blobs.put(upload_key(m.id), upload.bytes);
  ctx.blobs.put(original_key(m.id), write_mesh_to_memory(mesh, MeshFormat::ply, {.binary = true}));
  const JobRecord job = new_job(ctx, PrepareJobSpec{}, owner, m.id);
  ctx.store.insert_model(m, job);
  slot.push(job);
  nlohmann::json view = model_view(m, &job);
  view["job_id"] = job.id;
  view["document"] = document_json(document.document(), surface);
  view["document"]["zipped"] = document.zipped();
  HttpResponse r = json_response(202, view);
  r.set_header("Location", links::model(m.id));
  return r;
}

namespace {

// A preparing model's view says how far its preparation is (a query for those only: few at a time).
nlohmann::json current_model_view(ApiContext& ctx, const OwnerRecord& owner, const ModelRecord& m) {
  if (m.state != ModelState::preparing) return model_view(m);
  const std::vector<JobRecord> jobs = ctx.store.model_jobs(owner.id, m.id, JobKind::prepare);
  return model_view(m, jobs.empty() ? nullptr : &jobs.back());
}

}  // namespace

HttpResponse list_models(ApiContext& ctx, HttpRequest& req) {
  const OwnerRecord& owner = owner_of(req);
  nlohmann::json list = nlohmann::json::array();
  for (const auto& m : ctx.store.models(owner.id)) list.push_back(current_model_view(ctx, owner, m));
  return json_response(200, {{"models", list}});
}

HttpResponse get_model(ApiContext& ctx, HttpRequest& req) {
  const OwnerRecord& owner = owner_of(req);
  return json_response(200, current_model_view(ctx, owner, owned_model(ctx, owner, req.path_params.at("id"))));
}

namespace {

// Deleting a model deletes what tracing its copies needs (its original): refused while copies were
// handed out, unless the request names the model again in ?confirm=.
void refuse_losing_copies(ApiContext& ctx, const OwnerRecord& owner, const std::string& id,
                          const std::string& confirm) {
  owned_model(ctx, owner, id);  // 404 before anything else
  if (confirm == id) return;
  const auto copies = ctx.store.embeddings(id);
  const auto handed_out = std::count_if(copies.begin(), copies.end(),
                                        [](const EmbeddingRecord& e) { return e.state == EmbeddingState::ready; });
  if (handed_out == 0) return;
  throw Conflict("model " + id + " has " + std::to_string(handed_out) + (handed_out == 1 ? " copy" : " copies") +
                     " handed out: deleting it deletes its original and their records, and none of them could "
                     "be traced again. To delete it anyway, confirm with its id (?confirm=" +
                     id + "; meshmark models delete " + id + " --force)",
                 {{"copies", handed_out}});
}

}  // namespace

HttpResponse delete_model(ApiContext& ctx, HttpRequest& req) {
  const std::string& id = req.path_params.at("id");
  refuse_losing_copies(ctx, owner_of(req), id, req.query_value("confirm"));
  const auto jobs = ctx.store.delete_model(owner_of(req).id, id);
  if (!jobs) throw NotFound("no model '" + id + "'");
  ctx.models.evict(id);
  for (const std::string& job : *jobs) {
    ctx.queue.cancel(job);  // a queued one is dropped, a running one stops at its next check
    ctx.blobs.remove_prefix(job_prefix(job));
  }
  ctx.blobs.remove_prefix(model_prefix(id));
  HttpResponse r;
  r.status = 204;
  return r;
}

HttpResponse list_embeddings(ApiContext& ctx, HttpRequest& req) {
  const ModelRecord m = owned_model(ctx, owner_of(req), req.path_params.at("id"));
  nlohmann::json list = nlohmann::json::array();
  for (const auto& e : ctx.store.embeddings(m.id)) list.push_back(embedding_view(e));
  return json_response(200, {{"embeddings", list}});
}

void check_model_usable(ApiContext& ctx, HttpRequest& req) { usable_model(ctx, req); }

namespace {

std::vector<EmbedRequest> embed_requests(const ModelRecord& m, const nlohmann::json& body) {
  std::vector<EmbedRequest> requests;
  try {
    requests = parse_embed_requests(body);
  } catch (const std::invalid_argument& e) {
    throw InvalidRequest(e.what());
  }
  const std::string& format = requests.front().format;  // the same for every copy of a batch
  const auto asked = format.empty() ? std::nullopt : parse_mesh_format(format);
  if (asked && format != m.format &&
      (*asked == MeshFormat::glb || *asked == MeshFormat::gltf || *asked == MeshFormat::threemf))
    throw InvalidRequest("a marked " + format + " comes only from a " + format + " original; ask for " + m.format +
                         " (the file kept whole) or a plain obj, off, ply or stl mesh");
  return requests;
}

// Records the copy and the job that makes it (its payload as asked, or a fresh one unique within
// the model: 64 bits, or what a small mesh keeps robustly) and queues the job in `slot`.
nlohmann::json accept_copy(ApiContext& ctx, const OwnerRecord& owner, const ModelRecord& m, const EmbedRequest& request,
                           QueueSlot& slot) {
  EmbedJobSpec spec{request, new_id("emb_"), request.format.empty() ? m.format : request.format, ""};
  JobRecord job = new_job(ctx, spec, owner, m.id);
  EmbeddingRecord e{spec.embedding_id,
                    m.id,
                    owner.id,
                    "",
                    request.recipient,
                    job.id,
                    request.options,
                    ctx.clock.now_iso8601(),
                    EmbeddingState::pending,
                    request.requested_by};
  auto record = [&](const std::string& payload) {
    e.payload = spec.assigned_payload = payload;
    job.spec = spec;
    return ctx.store.insert_embedding(e, job);
  };
  if (request.payload) {
    if (!record(*request.payload))
      throw Conflict("this model already has a copy with payload " + *request.payload + "; see its embeddings");
  } else {
    const int robust = m.report.value("robust_payload_bits", 64);
    const int bytes = assigned_payload_bits(robust) / 8;
    bool stored = false;
    for (int attempt = 0; attempt < 16 && !stored; ++attempt) stored = record(random_hex(bytes));
    if (!stored) throw std::runtime_error("could not assign a unique payload");
  }
  slot.push(job);
  return {{"job_id", job.id},         {"embedding_id", e.id},           {"payload", e.payload},
          {"recipient", e.recipient}, {"requested_by", e.requested_by}, {"links", {{"job", links::job(job.id)}}}};
}

}  // namespace

HttpResponse embed(ApiContext& ctx, HttpRequest& req) {
  const OwnerRecord& owner = owner_of(req);
  const ModelRecord m = usable_model(ctx, req);
  const nlohmann::json body = json_body(req);
  const std::vector<EmbedRequest> requests = embed_requests(m, body);
  std::deque<QueueSlot> slots;  // every place first: a batch the queue cannot hold whole is refused whole
  for (std::size_t k = 0; k < requests.size(); ++k) slots.emplace_back(ctx.queue, owner.id);
  if (!body.contains("recipients")) {
    const nlohmann::json accepted = accept_copy(ctx, owner, m, requests.front(), slots.front());
    HttpResponse r = json_response(202, accepted);
    r.set_header("Location", links::job(accepted["job_id"]));
    return r;
  }
  nlohmann::json copies = nlohmann::json::array();
  for (std::size_t k = 0; k < requests.size(); ++k) copies.push_back(accept_copy(ctx, owner, m, requests[k], slots[k]));
  return json_response(202, {{"copies", copies}});
}

}  // namespace meshmark::server::handlers
