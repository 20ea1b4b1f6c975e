#include "server/jobs/job_runner.hpp"

#include <malloc.h>

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
#include "core/verification/read_back.hpp"
#include "core/verification/verify_copy.hpp"
#include "core/watermark/carrier_cache.hpp"
#include "core/watermark/combine_evidence.hpp"
#include "core/watermark/spread_plan.hpp"
#include "core/watermark/trace_copies.hpp"
#include "core/watermark/watermark.hpp"
#include "proto/api.hpp"
#include "proto/core_json.hpp"
#include "proto/links.hpp"
#include "server/clock.hpp"
#include "server/jobs/job_queue.hpp"
#include "server/store/storage_error.hpp"
#include "server/jobs/recover_jobs.hpp"
#include "server/store/job_transitions.hpp"
#include "server/secrets.hpp"
#include "server/store/blob_keys.hpp"

namespace meshmark::server {

namespace {

// glibc keeps what a job freed in its arenas: a daemon that parsed one large mesh would hold its
// peak for good, so a hoard beyond an eighth of the memory ceiling (at most 256 MiB) goes back to
// the system. Less is kept: memory handed back is faulted in anew by the next job (on the bunny,
// a tenth of an embed job's time went to page faults when every job trimmed).
void release_freed_heap(const MemoryBudget& memory) {
  const std::size_t kept = std::min(memory.ceiling() / 8, std::size_t{256} << 20);
  if (mallinfo2().fordblks > kept) malloc_trim(0);
}

using Steady = std::chrono::steady_clock;

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
    spdlog::error("job {} ({}) failed: {}", job.id, to_string(job.kind()), e.what());
  } catch (...) {
    spdlog::error("job {} ({}) failed: unknown exception", job.id, to_string(job.kind()));
  }
  return "internal error";
}

}  // namespace

void JobRunner::run(const std::string& job_id, const std::atomic<bool>& cancel) {
  try {
    run_job(job_id, cancel);
  } catch (const StorageError& e) {
    if (e.retryable()) throw RetryLater(e.what());
    throw;
  }
}

namespace {

// Progress is for people watching; every write is a durable (fsynced) commit, which costs whole
// seconds on a slow disk: within a stage, at most one a second. Each stage's time goes to the
// metrics when the next one starts. A job this attempt no longer holds (canceled, deleted, or
// started again elsewhere) stops at its next report.
class ProgressWriter {
 public:
  ProgressWriter(Store& store, Metrics& metrics, JobRecord& job)
      : store_(store), metrics_(metrics), job_(job), last_write_(Steady::now()) {}

  void report(const std::string& next, double progress) {
    const auto now = Steady::now();
    if (next == stage_ && (progress < job_.progress + 0.01 || now - last_write_ < std::chrono::seconds(1))) return;
    last_write_ = now;
    if (next != stage_) {
      end_stage(now);
      stage_ = next;
      stage_start_ = now;
    }
    job_.stage = next;
    job_.progress = progress;
    if (store_.save_progress(job_) != JobWrite::written) throw Canceled();  // the job is no longer this attempt's
  }
  void end_stage(Steady::time_point now) {
    if (!stage_.empty())
      metrics_.observe_stage(to_string(job_.kind()), stage_, std::chrono::duration<double>(now - stage_start_).count());
  }

 private:
  Store& store_;
  Metrics& metrics_;
  JobRecord& job_;
  std::string stage_;
  Steady::time_point stage_start_, last_write_;
};

}  // namespace

void JobRunner::run_job(const std::string& job_id, const std::atomic<bool>& cancel) {
  auto found = store_.job_by_id(job_id);
  if (!found || found->finished()) return;  // canceled or deleted while queued
  JobRecord job = *found;
  if (job.lease_owner != instance_) return;  // another daemon claimed it or took it over: theirs to run
  if (job.cancel_requested) return finish_canceled(store_, job, clock_);  // asked to stop before a restart
  // Its model is prepared by a job this queue does not hold (another daemon's): wait, queued.
  if (job.kind() != JobKind::prepare) {
    const auto model = store_.model_by_id(job.model_id);
    if (model && model->state == ModelState::preparing) throw RetryLater("its model is still being prepared");
  }
  start_job(job, clock_.now_iso8601());
  if (store_.start_job(job) != JobWrite::written) return;  // canceled, deleted or started elsewhere meanwhile

  const auto start = Steady::now();
  ProgressWriter progress(store_, metrics_, job);
  JobControl control;
  control.cancel = &cancel;
  control.deadline = start + std::chrono::seconds(config_.job_time_limit_seconds);
  control.threads = config_.threads_per_job;
  control.report = [&](const std::string& stage, double fraction) { progress.report(stage, fraction); };
  execute(job, control);
  progress.end_stage(Steady::now());
  record_outcome(job);
  release_freed_heap(memory_);
  metrics_.observe_job(to_string(job.kind()), to_string(job.state),
                       std::chrono::duration<double>(Steady::now() - start).count());
  spdlog::info("job {} ({}) {}{}", job.id, to_string(job.kind()), to_string(job.state),
               job.error.empty() ? "" : ": " + job.error);
}

void JobRunner::execute(JobRecord& job, const JobControl& control) {
  try {
    const MemoryReservation memory = reserve_memory(job, control);
    nlohmann::json result;
    switch (job.kind()) {
      case JobKind::prepare:
        result = prepare(job, control);
        break;
      case JobKind::embed:
        result = embed(job, control);
        break;
      case JobKind::detect:
        result = detect(job, control);
        break;
    }
    succeed_job(job, std::move(result), clock_.now_iso8601());
  } catch (const Canceled&) {
    cancel_job(job, clock_.now_iso8601());
  } catch (const TimeLimitExceeded&) {
    fail_job(job, "the job ran longer than its limit of " + std::to_string(config_.job_time_limit_seconds) + " s",
             clock_.now_iso8601());
  } catch (const StorageError& e) {
    if (e.retryable()) throw;  // the queue retries the job when the store takes it again
    fail_job(job, public_error(job), clock_.now_iso8601());
  } catch (...) {
    fail_job(job, public_error(job), clock_.now_iso8601());
  }
}

MemoryReservation JobRunner::reserve_memory(const JobRecord& job, const JobControl& control) {
  const auto model = store_.model_by_id(job.model_id);
  const auto model_vertices = static_cast<std::size_t>(model ? model->vertices : 0);
  const auto* detect = std::get_if<DetectJobSpec>(&job.spec);
  const auto suspect_vertices = static_cast<std::size_t>(detect ? detect->suspect_vertices : 0);
  // A job larger than most of the ceiling runs with the rest left to requests: uploads and small
  // jobs are not refused for the minutes a large model takes.
  const std::size_t cost =
      std::min(kJobBytesPerVertex * (model_vertices + suspect_vertices), memory_.ceiling() / 4 * 3);
  models_.make_room(cost);
  if (auto now = memory_.try_reserve(cost)) return std::move(*now);
  control.checkpoint("waiting for memory", 0.0);
  return memory_.reserve(cost, control);
}

void JobRunner::record_outcome(const JobRecord& job) {
  const JobWrite written = store_.finish_job(job);
  if (written == JobWrite::lost) spdlog::warn("job {}: its end was not written (it ended or moved meanwhile)", job.id);
  if (written != JobWrite::gone) return;
  // The model was deleted while the job ran: leave no files of it behind.
  blobs_.remove_prefix(job_prefix(job.id));
  if (job.kind() == JobKind::prepare) {
    models_.evict(job.model_id);
    blobs_.remove_prefix(model_prefix(job.model_id));
  }
}

std::shared_ptr<const PreparedEntry> JobRunner::model_for(const JobRecord& job, const JobControl& control) {
  const auto model = store_.model_by_id(job.model_id);
  if (!model) throw Canceled();  // the model was deleted
  if (model->state == ModelState::failed) throw InputError("the model failed to prepare: " + model->error);
  if (model->state != ModelState::ready) throw std::runtime_error("the model is not prepared yet");
  return preparer_.prepared(job.model_id, &control);
}

nlohmann::json JobRunner::prepare(JobRecord& job, const JobControl& control) {
  const auto entry = preparer_.prepare(job.model_id, &control);
  const PreparedModel& m = entry->model;
  nlohmann::json result = {{"basis", basis_json(m)}, {"seconds", m.prepare_seconds}};
  // The payload the default scheme keeps through simplification and remeshing on this model:
  // payloads the daemon assigns are no longer (models_handlers.cpp).
  const CarrierField& field = carrier_cache(m).field(m, WatermarkOptions{}.wavelet, control.threads);
  const int capacity = payload_capacity_bits(field, WatermarkOptions{});
  if (capacity < kMinAssignedPayloadBits)
    throw InputError("the mesh carries " +
                     (capacity > 0 ? "at most " + std::to_string(capacity) + " bits" : std::string("no payload")) +
                     ", and every copy the daemon hands out carries at least " +
                     std::to_string(kMinAssignedPayloadBits) + " (a payload of its own per recipient)");
  const int robust = robust_payload_bits(field, WatermarkOptions{});
  result["robust_payload_bits"] = robust;
  result["payload_capacity_bits"] = capacity;
  store_.set_model_payload_capacity(job.model_id, robust);
  if (m.spherical()) {
    result["grid"] = {{"base", to_string(m.base)}, {"level", m.level()}, {"samples", m.sample_count()}};
    result["parameterization"] = m.param;
  }
  return result;
}

nlohmann::json JobRunner::embed(JobRecord& job, const JobControl& control) {
  const auto& spec = std::get<EmbedJobSpec>(job.spec);
  const Bits payload = bits_from_hex(spec.assigned_payload);
  const auto entry = model_for(job, control);
  const std::string key = owner_watermark_key(master_key_, job.owner_id);
  const EmbedResult result = embed_watermark(entry->model, key, payload, spec.request.options, &control);
  checkpoint(&control, "write", 0.9);
  const MarkedCopy copy = write_marked_copy(job, spec.output_format, entry->model, result.mesh, control);
  // Nothing is handed out that the detector has not read back (verify_copy.hpp).
  const JobControl verifying = rescaled(control, 0.0, 1.0, 0.92, 0.99);
  Mesh as_written =
      read_back(copy.bytes, *parse_mesh_format(spec.output_format), upload_read_options(config_, &control));
  VerifyOptions verify;
  verify.registration_proven = entry->registration_proven.load();
  const CopyVerification verification = verify_copy(entry->model, entry->target, std::move(as_written), key, payload,
                                                    spec.request.options, verify, &verifying);
  require_readable(verification, payload);
  entry->registration_proven = true;
  blobs_.put(output_key(job.id, spec.output_format), copy.bytes);
  return embed_result(job, spec, result, copy, verification);
}

nlohmann::json JobRunner::embed_result(const JobRecord& job, const EmbedJobSpec& spec, const EmbedResult& result,
                                       const MarkedCopy& copy, const CopyVerification& verification) {
  return {{"embedding_id", spec.embedding_id},
          {"payload", spec.assigned_payload},
          {"recipient", spec.request.recipient},
          {"format", spec.output_format},
          {"zipped", copy.zipped},
          {"kept_whole", copy.kept_whole},
          {"parameters", spec.request.options},
          {"carriers", result.carriers},
          {"rms_displacement", result.rms_displacement},
          {"max_displacement", result.max_displacement},
          {"warnings", result.warnings},
          {"verification", verification},
          {"download", links::job_result(job.id)}};
}

// The marked copy: the uploaded file with its positions moved (every other byte kept) when it is
// asked for in the model's own format; else (another format, or a model stored before uploads
// were kept) the marked surface as a plain mesh.
JobRunner::MarkedCopy JobRunner::write_marked_copy(const JobRecord& job, const std::string& format,
                                                   const PreparedModel& model, const Mesh& marked,
                                                   const JobControl& control) {
  const MeshFormat f = *parse_mesh_format(format);
  const auto upload = parsed_upload(job.model_id, f, control);
  if (!upload)
    return {write_mesh_to_memory(marked, f, {.binary = f == MeshFormat::ply || f == MeshFormat::stl}), false, false};
  if (!same_connectivity(upload->surface.mesh, model.mesh))
    throw std::runtime_error("the model's stored file does not match its prepared surface");
  const MovedSlots moved = move_slots(upload->document.document(), upload->surface, marked.V);
  return {upload->document.write(moved.positions, moved.rotations), upload->document.zipped(), true};
}

// The model's upload, parsed, when it was stored in `format`: kept with the model after its first
// copy. Read without the job's control, which the kept document would outlive; the upload was
// read under the same limits when it arrived.
std::shared_ptr<const ParsedUpload> JobRunner::parsed_upload(const std::string& model_id, MeshFormat format,
                                                             const JobControl& control) {
  if (auto kept = models_.upload(model_id, format)) return kept;
  const auto record = store_.model_by_id(model_id);
  if (!record || parse_mesh_format(record->format) != format) return nullptr;
  auto bytes = blobs_.get(upload_key(model_id));
  if (!bytes) return nullptr;
  control.poll();
  DocumentReadOptions options;
  options.limits = upload_read_options(config_, nullptr);
  const std::size_t size = bytes->size();
  auto upload = std::make_shared<const ParsedUpload>(std::move(*bytes), format, options);
  models_.keep_upload(model_id, upload,
                      upload_memory_cost(size, static_cast<std::size_t>(upload->surface.mesh.V.rows())));
  return upload;
}

namespace {

// The bits a reading got wrong of a copy's payload; null when they differ in length.
nlohmann::json bit_errors(const Bits& read, const Bits& payload) {
  if (read.size() != payload.size()) return nullptr;
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < read.size(); ++i) wrong += read[i] != payload[i];
  return wrong;
}

}  // namespace

nlohmann::json JobRunner::detect(JobRecord& job, const JobControl& control) {
  const DetectRequest& request = std::get<DetectJobSpec>(job.spec).request;
  const auto bytes = blobs_.get(suspect_key(job.id));
  if (!bytes) throw std::runtime_error("the suspect mesh is missing from the store");
  const Mesh suspect = read_mesh_from_memory(*bytes, MeshFormat::ply, {}, "suspect").mesh;
  const auto entry = model_for(job, control);
  // Every copy handed out is a candidate, read with the settings it was made with (trace_copies).
  std::vector<EmbeddingRecord> made;
  std::vector<KnownCopy> copies;
  for (const EmbeddingRecord& e : store_.embeddings(job.model_id)) {
    if (e.state != EmbeddingState::ready) continue;  // a copy that was never made cannot have been passed on
    made.push_back(e);
    copies.push_back({bits_from_hex(e.payload), parse_scheme(e.parameters.value("scheme", "spread")),
                      parse_wavelet_type(e.parameters.value("wavelet", "linear-lifting"))});
  }
  TraceOptions options;
  options.detect.watermark = request.options;
  options.detect.payload_bits = request.bits;
  // The request's settings are read only when asked for: each copy is read with its own anyway.
  options.read_asked = request.settings_given;
  const Tracing tracing = trace_copies(entry->model, suspect, owner_watermark_key(master_key_, job.owner_id), copies,
                                       options, &entry->target, &control);
  nlohmann::json out = tracing.result;
  out["readings"] = tracing.readings;
  nlohmann::json matches = nlohmann::json::array();  // the closest few, best first
  for (std::size_t k = 0; k < std::min(tracing.ranked.size(), kListedCandidates); ++k) {
    const EmbeddingRecord& e = made[tracing.ranked[k].copy];
    const double log10_p = tracing.ranked[k].log10_p_value;
    matches.push_back({{"embedding_id", e.id},
                       {"recipient", e.recipient},
                       {"payload", e.payload},
                       {"log10_p_value", log10_p},
                       {"p_value", std::pow(10.0, log10_p)},
                       {"bit_errors", bit_errors(tracing.result.decoded, copies[tracing.ranked[k].copy].payload)}});
  }
  out["matches"] = matches;
  out["match"] = tracing.match ? matches[0] : nlohmann::json(nullptr);
  out["match_threshold_log10_p"] = options.match_log10_p;
  out["detected"] = tracing.result.detected;  // the one decision (combine_evidence.hpp), the copies' test included
  return out;
}

}  // namespace meshmark::server
