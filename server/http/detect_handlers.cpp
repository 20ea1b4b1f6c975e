// Detections: a suspect checked against one model (POST /v1/models/{id}/detect), or searched for
// across the owner's library (POST /v1/detect): the models whose shape is closest are
// short-listed by their signatures, and the suspect is checked against each of those.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <limits>

#include "core/io/document_surface.hpp"
#include "core/io/write_mesh.hpp"
#include "core/registration/shape_signature.hpp"
#include "core/util/keyed_random.hpp"
#include "proto/links.hpp"
#include "server/http/api_error.hpp"
#include "server/http/handler_support.hpp"
#include "server/http/handlers.hpp"
#include "server/http/problem.hpp"
#include "server/http/upload_parsing.hpp"
#include "server/http/views.hpp"
#include "server/store/blob_keys.hpp"

namespace meshmark::server::handlers {

namespace {

constexpr int kDefaultCandidates = 3, kMaxCandidates = 10;

// The suspect's surface: every instance of the scene, welded.
Mesh suspect_surface(const ParsedUpload& upload) {
  const Mesh scene = upload.document.document().scene();
  return weld_positions(scene.V, scene.F).mesh;
}

// A suspect as the detect jobs keep it: its surface, and the digest of the file it came in.
struct Suspect {
  Mesh surface;
  std::string sha256;
  std::string ply() const { return write_mesh_to_memory(surface, MeshFormat::ply, {.binary = true}); }
};

Suspect read_suspect(ApiContext& ctx, HttpRequest& req) {
  const ParsedUpload upload = parse_upload(req, format_param(req), ctx);
  return {suspect_surface(upload), sha256_hex(upload.bytes)};
}

// Queues a detection of `suspect` against `model_id` in the place `slot` holds; its job's view.
nlohmann::json queue_detection(ApiContext& ctx, const OwnerRecord& owner, const std::string& model_id,
                               const DetectRequest& request, const Suspect& suspect, const std::string& suspect_ply,
                               QueueSlot& slot) {
  const JobRecord job = new_job(ctx, DetectJobSpec{request, suspect.surface.V.rows(), suspect.sha256}, owner, model_id);
  ctx.blobs.put(suspect_key(job.id), suspect_ply);
  ctx.store.insert_job(job);
  slot.push(job);
  return {{"job_id", job.id}, {"links", {{"job", links::job(job.id)}}}};
}

int candidates_param(const HttpRequest& req) {
  if (!req.has_query("candidates")) return kDefaultCandidates;
  const std::string text = req.query_value("candidates");
  int n = 0;
  if (text.empty() || text.size() > 2 || !std::all_of(text.begin(), text.end(), ::isdigit) ||
      (n = std::stoi(text)) < 1 || n > kMaxCandidates)
    throw InvalidRequest("'candidates' must be 1 to " + std::to_string(kMaxCandidates));
  return n;
}

struct Candidate {
  ModelRecord model;
  double distance;  // of the shape signatures; infinite for a model stored without one
};

// The owner's ready models, the closest shapes first.
std::vector<Candidate> ranked_models(ApiContext& ctx, const OwnerRecord& owner, const ShapeSignature& suspect) {
  std::vector<Candidate> ranked;
  for (ModelRecord& m : ctx.store.models(owner.id)) {
    if (m.state != ModelState::ready) continue;
    const auto stored = m.report.find(kShapeSignatureKey);
    const double d = stored == m.report.end()
                         ? std::numeric_limits<double>::infinity()
                         : signature_distance(suspect, signature_from_values(stored->get<std::vector<double>>()));
    ranked.push_back({std::move(m), d});
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  return ranked;
}

}  // namespace

void check_detect(ApiContext& ctx, HttpRequest& req) {
  usable_model(ctx, req);
  format_param(req);
  detect_params(req);
}

HttpResponse detect(ApiContext& ctx, HttpRequest& req) {
  const OwnerRecord& owner = owner_of(req);
  const ModelRecord m = usable_model(ctx, req);
  const DetectRequest request = detect_params(req);
  const Suspect suspect = read_suspect(ctx, req);
  QueueSlot slot(ctx.queue, owner.id);
  const nlohmann::json accepted = queue_detection(ctx, owner, m.id, request, suspect, suspect.ply(), slot);
  HttpResponse r = json_response(202, accepted);
  r.set_header("Location", accepted["links"]["job"]);
  return r;
}

void check_library_detect(ApiContext&, HttpRequest& req) {
  format_param(req);
  detect_params(req);
  candidates_param(req);
}

HttpResponse detect_in_library(ApiContext& ctx, HttpRequest& req) {
  const OwnerRecord& owner = owner_of(req);
  const DetectRequest request = detect_params(req);
  const int wanted = candidates_param(req);
  const Suspect suspect = read_suspect(ctx, req);
  const std::vector<Candidate> ranked = ranked_models(ctx, owner, shape_signature(suspect.surface));
  if (ranked.empty()) throw NotFound("you have no prepared model to search: upload your originals first");
  const std::size_t n = std::min(ranked.size(), static_cast<std::size_t>(wanted));
  std::deque<QueueSlot> slots;  // every place first: the whole search is queued, or none of it
  for (std::size_t k = 0; k < n; ++k) slots.emplace_back(ctx.queue, owner.id);
  const std::string suspect_ply = suspect.ply();
  nlohmann::json candidates = nlohmann::json::array();
  for (std::size_t k = 0; k < n; ++k) {
    nlohmann::json c = queue_detection(ctx, owner, ranked[k].model.id, request, suspect, suspect_ply, slots[k]);
    c["model_id"] = ranked[k].model.id;
    c["model_name"] = ranked[k].model.name;
    c["shape_distance"] = std::isfinite(ranked[k].distance) ? nlohmann::json(ranked[k].distance) : nlohmann::json();
    candidates.push_back(c);
  }
  return json_response(202, {{"models_compared", ranked.size()}, {"candidates", candidates}});
}

}  // namespace meshmark::server::handlers
