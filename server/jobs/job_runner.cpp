#include "server/jobs/job_runner.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <tuple>

#include "core/io/document_surface.hpp"
#include "core/io/packaged_document.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"
#include "core/param/sphere_param.hpp"
#include "core/util/input_error.hpp"
#include "core/watermark/carrier_field.hpp"
#include "core/watermark/combine_evidence.hpp"
#include "core/watermark/spread_plan.hpp"
#include "core/watermark/watermark.hpp"
#include "proto/api.hpp"
#include "proto/core_json.hpp"
#include "proto/links.hpp"
#include "server/clock.hpp"
#include "server/jobs/job_queue.hpp"
#include "server/store/storage_error.hpp"
#include "server/jobs/recover_jobs.hpp"
#include "server/secrets.hpp"

namespace meshmark::server {

std::string job_prefix(const std::string& job_id) { return "jobs/" + job_id; }
std::string suspect_key(const std::string& job_id) { return job_prefix(job_id) + "/suspect.ply"; }
std::string output_key(const std::string& job_id, const std::string& format) {
  return job_prefix(job_id) + "/output." + format;
}

namespace {

using Clock = std::chrono::steady_clock;

// A detection is reported as matching a recorded copy below this p-value (over all copies).
constexpr double kMatchLog10P = -6;
constexpr std::size_t kListedCandidates = 5;

}  // namespace

namespace {

// What a user may read of a failure: the core's complaints about the input; nothing else.
std::string public_error(const JobRecord& job) {
  try {
    throw;
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::invalid_argument& e) {
    return e.what();
  } catch (const std::exception& e) {
    spdlog::error("job {} ({}) failed: {}", job.id, job.kind, e.what());
  } catch (...) {
    spdlog::error("job {} ({}) failed: unknown exception", job.id, job.kind);
  }
  return "internal error";
}

}  // namespace

void JobRunner::run(const std::string& job_id, const std::atomic<bool>& cancel) {
  try {
    run_job(job_id, cancel);
  } catch (const StorageError& e) {
    if (e.full()) throw RetryLater(e.what());
    throw;
  }
}

void JobRunner::run_job(const std::string& job_id, const std::atomic<bool>& cancel) {
  auto found = store_.job_by_id(job_id);
  if (!found || found->finished()) return;  // canceled or deleted while queued
  JobRecord job = *found;
  if (job.cancel_requested) return finish_canceled(store_, job);  // asked to stop before a restart
  job.state = "running";
  job.attempts += 1;
  job.started_at = now_iso8601();
  job.stage = "starting";
  store_.update_job(job);

  const auto start = Clock::now();
  auto stage_start = start;
  std::string stage;
  JobControl control;
  control.cancel = &cancel;
  control.deadline = start + std::chrono::seconds(config_.job_time_limit_seconds);
  auto last_write = start;
  control.report = [&](const std::string& next, double progress) {
    // Progress is for people watching; every write is a durable (fsynced) commit, which costs
    // whole seconds on a slow disk: within a stage, at most one a second.
    const auto now = Clock::now();
    if (next == stage && (progress < job.progress + 0.01 || now - last_write < std::chrono::seconds(1))) return;
    last_write = now;
    if (next != stage) {
      if (!stage.empty()) metrics_.observe_stage(job.kind, stage, std::chrono::duration<double>(now - stage_start).count());
      stage = next;
      stage_start = now;
    }
    job.stage = next;
    job.progress = progress;
    store_.update_job(job);
  };

  try {
    if (job.kind == "prepare") job.result = prepare(job, control);
    else if (job.kind == "embed") job.result = embed(job, control);
    else if (job.kind == "detect") job.result = detect(job, control);
    else throw std::logic_error("unknown job kind '" + job.kind + "'");
    job.state = "succeeded";
    job.progress = 1;
  } catch (const Canceled&) {
    job.state = "canceled";
    job.error = "canceled";
  } catch (const TimeLimitExceeded&) {
    job.state = "failed";
    job.error = "the job ran longer than its limit of " + std::to_string(config_.job_time_limit_seconds) + " s";
  } catch (const StorageError& e) {
    if (e.full()) throw;  // the queue retries the job when the store takes it again
    job.state = "failed";
    job.error = public_error(job);
  } catch (...) {
    job.state = "failed";
    job.error = public_error(job);
  }
  if (!stage.empty()) metrics_.observe_stage(job.kind, stage, std::chrono::duration<double>(Clock::now() - stage_start).count());
  job.stage = job.state == "succeeded" ? "done" : job.stage;
  job.finished_at = now_iso8601();
  record_outcome(job);
  metrics_.observe_job(job.kind, job.state, std::chrono::duration<double>(Clock::now() - start).count());
  spdlog::info("job {} ({}) {}{}", job.id, job.kind, job.state, job.error.empty() ? "" : ": " + job.error);
}

void JobRunner::record_outcome(const JobRecord& job) {
  if (job.kind == "prepare")
    store_.set_model_state(job.model_id, job.state == "succeeded" ? "ready" : "failed", job.error);
  if (job.kind == "embed")
    store_.finish_embedding(job.request.value("embedding_id", ""), job.state == "succeeded");
  store_.update_job(job);
  // The model was deleted while the job ran: leave no files of it behind.
  if (!store_.job_by_id(job.id)) blobs_.remove_prefix(job_prefix(job.id));
  if (job.kind == "prepare" && !store_.model_by_id(job.model_id)) {
    models_.evict(job.model_id);
    blobs_.remove_prefix(model_prefix(job.model_id));
  }
}

nlohmann::json JobRunner::prepare(JobRecord& job, const JobControl& control) {
  const auto entry = models_.get(job.model_id, &control);
  const PreparedModel& m = entry->model;
  nlohmann::json result = {{"basis", basis_json(m)}, {"seconds", m.prepare_seconds}};
  // The payload the default scheme keeps through simplification and remeshing on this model:
  // payloads the daemon assigns are no longer (models_handlers.cpp).
  const int robust = robust_payload_bits(CarrierField(m, WatermarkOptions{}.wavelet), WatermarkOptions{});
  result["robust_payload_bits"] = robust;
  store_.set_model_payload_capacity(job.model_id, robust);
  if (m.spherical()) {
    result["grid"] = {{"base", to_string(m.base)}, {"level", m.level()}, {"samples", m.sample_count()}};
    result["parameterization"] = m.param;
  }
  return result;
}

nlohmann::json JobRunner::embed(JobRecord& job, const JobControl& control) {
  // Jobs queued before the request was kept apart carry it flat, with the daemon's keys.
  nlohmann::json asked = job.request.contains("request") ? job.request.at("request") : job.request;
  if (!job.request.contains("request"))
    for (const char* daemon_key : {"embedding_id", "output_format", "assigned_payload"}) asked.erase(daemon_key);
  const EmbedRequest request = parse_embed_request(asked);
  const std::string payload_hex = job.request.at("assigned_payload").get<std::string>();
  const auto entry = models_.get(job.model_id, &control);
  const std::string key = owner_watermark_key(master_key_, job.owner_id);
  const EmbedResult result = embed_watermark(entry->model, key, bits_from_hex(payload_hex), request.options, &control);
  checkpoint(&control, "write", 0.9);
  const std::string format = job.request.at("output_format").get<std::string>();
  const MarkedCopy copy = write_marked_copy(job, format, entry->model, result.mesh, control);
  blobs_.put(output_key(job.id, format), copy.bytes);
  return {{"embedding_id", job.request.at("embedding_id")},
          {"payload", payload_hex},
          {"recipient", request.recipient},
          {"format", format},
          {"zipped", copy.zipped},
          {"kept_whole", copy.kept_whole},
          {"parameters", request.options},
          {"carriers", result.carriers},
          {"rms_displacement", result.rms_displacement},
          {"max_displacement", result.max_displacement},
          {"warnings", result.warnings},
          {"download", links::job_result(job.id)}};
}

// The marked copy: the uploaded file with its positions moved (every other byte kept) when it is
// asked for in the model's own format; else (another format, or a model stored before uploads
// were kept) the marked surface as a plain mesh.
JobRunner::MarkedCopy JobRunner::write_marked_copy(const JobRecord& job, const std::string& format, const PreparedModel& model,
                                                   const Mesh& marked, const JobControl& control) {
  const auto record = store_.model_by_id(job.model_id);
  const auto upload = blobs_.get(upload_key(job.model_id));
  const MeshFormat f = *parse_mesh_format(format);
  if (record && upload && record->format == format) {
    DocumentReadOptions options;
    options.limits = upload_read_options(config_, &control);
    const PackagedDocument document(*upload, f, options, "the model's file");
    const WeldedSurface surface = document_surface(document.document());
    if (surface.mesh.V.rows() != model.mesh.V.rows() || surface.mesh.F != model.mesh.F)
      throw std::runtime_error("the model's stored file does not match its prepared surface");
    const MovedSlots moved = move_slots(document.document(), surface, marked.V);
    return {document.write(moved.positions, moved.rotations), document.zipped(), true};
  }
  return {write_mesh_to_memory(marked, f, {.binary = f == MeshFormat::ply || f == MeshFormat::stl}), false, false};
}

nlohmann::json JobRunner::detect(JobRecord& job, const JobControl& control) {
  const DetectRequest request = parse_detect_query(job.request.value("scheme", ""), job.request.value("wavelet", ""),
                                                   std::to_string(job.request.value("bits", 64)));
  const auto bytes = blobs_.get(suspect_key(job.id));
  if (!bytes) throw std::runtime_error("the suspect mesh is missing from the store");
  const Mesh suspect = read_mesh_from_memory(*bytes, MeshFormat::ply, {}, "suspect").mesh;
  const auto entry = models_.get(job.model_id, &control);
  // Every copy handed out is a candidate, read with the settings it was made with: copies are
  // grouped by (scheme, wavelet, payload bits), and each group is one reading whose known-copy
  // test covers its copies. The request's own settings are always read (its blind decode).
  using Settings = std::tuple<std::string, std::string, int>;
  const Settings asked{to_string(request.options.scheme), to_string(request.options.wavelet), request.bits};
  std::map<Settings, std::vector<EmbeddingRecord>> groups{{asked, {}}};
  for (const EmbeddingRecord& e : store_.embeddings(job.model_id)) {
    if (e.state != "ready") continue;  // a copy that was never made cannot have been passed on
    groups[Settings{e.parameters.value("scheme", "spread"), e.parameters.value("wavelet", "linear-lifting"),
                    static_cast<int>(bits_from_hex(e.payload).size())}]
        .push_back(e);
  }
  const std::string key = owner_watermark_key(master_key_, job.owner_id);
  std::optional<DetectResult> best;
  std::vector<EmbeddingRecord> candidates;  // those of the reading that decided
  for (const auto& [settings, copies] : groups) {
    DetectOptions options;
    options.watermark = request.options;
    options.watermark.scheme = parse_scheme(std::get<0>(settings));
    options.watermark.wavelet = parse_wavelet_type(std::get<1>(settings));
    options.payload_bits = std::get<2>(settings);
    if (options.watermark.scheme == Scheme::paper && !entry->model.spherical()) continue;
    for (const EmbeddingRecord& e : copies) options.candidates.push_back(bits_from_hex(e.payload));
    DetectResult r = detect_watermark(entry->model, suspect, key, options, &entry->target, &control);
    if (!best || r.log10_p_value < best->log10_p_value) best = std::move(r), candidates = copies;
  }
  if (!best) throw std::runtime_error("no reading applies to this model");
  charge_for_readings(*best, static_cast<int>(groups.size()), DetectOptions{}.false_alarm);
  const DetectResult& r = *best;
  nlohmann::json out = r;
  out["readings"] = groups.size();
  // Each copy's p-value is already charged for the number of copies tried (Bonferroni).
  const double threshold = kMatchLog10P;
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return r.candidate_log10_p[a] < r.candidate_log10_p[b]; });
  nlohmann::json matches = nlohmann::json::array();  // the closest few, best first
  for (std::size_t k = 0; k < std::min<std::size_t>(order.size(), kListedCandidates); ++k) {
    const std::size_t i = order[k];
    matches.push_back({{"embedding_id", candidates[i].id},
                       {"recipient", candidates[i].recipient},
                       {"payload", candidates[i].payload},
                       {"log10_p_value", r.candidate_log10_p[i]},
                       {"p_value", std::pow(10.0, r.candidate_log10_p[i])}});
  }
  const bool matched = r.detected && !order.empty() && r.candidate_log10_p[order.front()] < threshold;
  out["matches"] = matches;
  out["match"] = matched ? matches[0] : nlohmann::json(nullptr);
  out["match_threshold_log10_p"] = threshold;
  out["detected"] = r.detected;  // the one decision (combine_evidence.hpp), the copies' test included
  return out;
}

}  // namespace meshmark::server
