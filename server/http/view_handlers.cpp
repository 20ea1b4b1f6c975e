// What a person looks at: a model's and a copy's surfaces for the console's 3D view (with the
// mark's displacement), a suspect as the detector aligned it, and a detection's evidence report.

#include <chrono>

#include "core/io/document_surface.hpp"
#include "core/io/packaged_document.hpp"
#include "core/io/read_mesh.hpp"
#include "core/render/preview_mesh.hpp"
#include "core/util/job_control.hpp"
#include "core/util/keyed_random.hpp"
#include "proto/core_json.hpp"
#include "server/clock.hpp"
#include "server/config.hpp"
#include "server/http/api_error.hpp"
#include "server/http/evidence_report.hpp"
#include "server/http/handler_support.hpp"
#include "server/http/handlers.hpp"
#include "server/store/blob_keys.hpp"
#include "server/store/store.hpp"

namespace meshmark::server::handlers {

namespace {

constexpr int kPictureSize = 360;

std::string blob_or_404(ApiContext& ctx, const std::string& key, const std::string& what) {
  auto bytes = ctx.blobs.get(key);
  if (!bytes) throw NotFound(what + " is no longer stored");
  return std::move(*bytes);
}

// A surface the daemon stored as binary PLY (an original's, a suspect's).
Mesh stored_surface(ApiContext& ctx, const std::string& key, const std::string& what) {
  return read_mesh_from_memory(blob_or_404(ctx, key, what), MeshFormat::ply, upload_read_options(ctx.config, nullptr),
                               what)
      .mesh;
}

HttpResponse ply_response(std::string body) {
  HttpResponse r;
  r.content_type = "application/octet-stream";
  r.body = std::move(body);
  return r;
}

// The marked copy as handed out, read back as a surface (within the job time limit).
Mesh copy_surface(ApiContext& ctx, const JobRecord& job) {
  const auto& spec = std::get<EmbedJobSpec>(job.spec);
  JobControl control;
  control.deadline = std::chrono::steady_clock::now() + std::chrono::seconds(ctx.config.job_time_limit_seconds);
  control.cancel = &ctx.draining;
  DocumentReadOptions options;
  options.limits = upload_read_options(ctx.config, &control);
  const PackagedDocument document(blob_or_404(ctx, output_key(job.id, spec.output_format), "the copy"),
                                  *parse_mesh_format(spec.output_format), options, "the copy");
  return document_surface(document.document()).mesh;
}

// The embedding the detection named, if any.
std::optional<EmbeddingRecord> named_copy(ApiContext& ctx, const JobRecord& detection) {
  const nlohmann::json& match = detection.result.contains("match") ? detection.result["match"] : nlohmann::json();
  if (!match.is_object()) return std::nullopt;
  const std::string id = match.value("embedding_id", std::string());
  for (const EmbeddingRecord& e : ctx.store.embeddings(detection.model_id))
    if (e.id == id) return e;
  return std::nullopt;
}

// The suspect of a finished detection, moved onto the original by the pose the detector found
// (the rigid part: a bent copy's unbending is not redone here).
Mesh aligned_suspect(ApiContext& ctx, const JobRecord& detection) {
  Mesh suspect = stored_surface(ctx, suspect_key(detection.id), "the suspect");
  const nlohmann::json& alignment = detection.result.value("alignment", nlohmann::json::object());
  if (!alignment.contains("transform")) return suspect;
  const Similarity pose = alignment.at("transform").get<Similarity>();
  suspect.V = pose.apply_to_rows(suspect.V);
  if (pose.R.determinant() < 0) suspect.F.col(1).swap(suspect.F.col(2));  // a mirrored copy: faces out again
  return suspect;
}

}  // namespace

HttpResponse model_preview(ApiContext& ctx, HttpRequest& req) {
  const ModelRecord m = owned_model(ctx, owner_of(req), req.path_params.at("id"));
  return ply_response(write_preview_ply(stored_surface(ctx, original_key(m.id), "the model's surface")));
}

HttpResponse job_preview(ApiContext& ctx, HttpRequest& req) {
  const JobRecord job = succeeded_job(ctx, req);
  if (job.kind() == JobKind::detect) return ply_response(write_preview_ply(aligned_suspect(ctx, job)));
  if (job.kind() != JobKind::embed) throw Conflict("only embed and detect jobs have a surface to show");
  const Mesh original = stored_surface(ctx, original_key(job.model_id), "the model's surface");
  const Mesh copy = copy_surface(ctx, job);
  if (!same_connectivity(copy, original)) return ply_response(write_preview_ply(copy));
  return ply_response(write_preview_ply(copy, normal_displacement_percent(original, copy.V)));
}

HttpResponse job_report(ApiContext& ctx, HttpRequest& req) {
  const JobRecord job = succeeded_job(ctx, req);
  if (job.kind() != JobKind::detect) throw Conflict("an evidence report is made of a detect job");
  EvidenceReport report;
  report.model = owned_model(ctx, owner_of(req), job.model_id);
  report.detection = job;
  report.copy = named_copy(ctx, job);
  if (auto upload = ctx.blobs.get(upload_key(job.model_id))) report.original_sha256 = sha256_hex(*upload);
  report.suspect_sha256 = std::get<DetectJobSpec>(job.spec).suspect_sha256;
  report.pictures = alignment_pictures(stored_surface(ctx, original_key(job.model_id), "the model's surface"),
                                       aligned_suspect(ctx, job), kPictureSize);
  report.generated_at = ctx.clock.now_iso8601();
  report.software = std::string("meshmark ") + MESHMARK_VERSION;
  HttpResponse r;
  r.content_type = "text/html; charset=utf-8";
  r.body = evidence_report_html(report);
  r.set_header("Content-Disposition", "attachment; filename=\"evidence-" + job.id + ".html\"");
  r.set_header("Content-Security-Policy", "default-src 'none'; style-src 'unsafe-inline'; img-src data:");
  return r;
}

}  // namespace meshmark::server::handlers
