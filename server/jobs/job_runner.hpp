#pragma once
// Runs one job to its end and records the outcome: prepare (parameterization and the rest,
// stored with the model), embed (writes the watermarked mesh), detect (reads a suspect, and
// names the recorded embedding it matches). Every failure becomes the job's error, except a full
// store, which the queue retries.

#include <atomic>
#include <string>

#include "core/verification/verify_copy.hpp"
#include "core/watermark/watermark.hpp"
#include "server/clock.hpp"
#include "server/config.hpp"
#include "server/jobs/model_preparer.hpp"
#include "server/memory_budget.hpp"
#include "server/metrics.hpp"
#include "server/model_cache.hpp"
#include "server/store/store.hpp"

namespace meshmark::server {

/// What a runner works with; the daemon's, or a test's.
struct JobServices {
  Store& store;
  BlobStore& blobs;
  ModelCache& models;
  MemoryBudget& memory;
  Metrics& metrics;
  const Clock& clock;
  std::string instance;  ///< this daemon's lease owner id: it starts only the jobs it holds
};

class JobRunner {
 public:
  JobRunner(const JobServices& services, const DaemonConfig& config, std::string master_key)
      : store_(services.store),
        blobs_(services.blobs),
        models_(services.models),
        preparer_(services.blobs, services.models),
        memory_(services.memory),
        metrics_(services.metrics),
        clock_(services.clock),
        instance_(services.instance),
        config_(config),
        master_key_(std::move(master_key)) {}

  /// Throws RetryLater when the store is full (the queue runs the job again later).
  void run(const std::string& job_id, const std::atomic<bool>& cancel);

 private:
  void run_job(const std::string& job_id, const std::atomic<bool>& cancel);
  // Runs the job's work and moves it to its final state (succeeded, failed or canceled).
  void execute(JobRecord& job, const JobControl& control);
  // Writes the finished job with its model's or copy's state (Store::finish_job); removes the
  // files of a job whose model was deleted while it ran.
  void record_outcome(const JobRecord& job);
  // The prepared model an embed or detect job uses; refuses one whose preparation failed.
  std::shared_ptr<const PreparedEntry> model_for(const JobRecord& job, const JobControl& control);
  // The job's working memory, taken from the daemon's ceiling; waits while others hold it.
  MemoryReservation reserve_memory(const JobRecord& job, const JobControl& control);
  nlohmann::json prepare(JobRecord& job, const JobControl& control);
  nlohmann::json embed(JobRecord& job, const JobControl& control);
  struct MarkedCopy {
    std::string bytes;
    bool zipped = false;      ///< a ZIP like the upload
    bool kept_whole = false;  ///< the upload with moved positions (else the marked surface only)
  };
  MarkedCopy write_marked_copy(const JobRecord& job, const std::string& format, const PreparedModel& model,
                               const Mesh& marked, const JobControl& control);
  std::shared_ptr<const ParsedUpload> parsed_upload(const std::string& model_id, MeshFormat format,
                                                    const JobControl& control);
  nlohmann::json embed_result(const JobRecord& job, const EmbedJobSpec& spec, const EmbedResult& result,
                              const MarkedCopy& copy, const CopyVerification& verification);
  nlohmann::json detect(JobRecord& job, const JobControl& control);

  Store& store_;
  BlobStore& blobs_;
  ModelCache& models_;
  ModelPreparer preparer_;
  MemoryBudget& memory_;
  Metrics& metrics_;
  const Clock& clock_;
  const std::string instance_;
  const DaemonConfig& config_;
  std::string master_key_;
};

}  // namespace meshmark::server
