#pragma once
// The daemon's durable records, behind an interface: SQLite is the embedded default
// (sqlite_store.hpp); a shared database is another implementation of the same calls. Every write
// is durable when the call returns. Owner scoping is part of the interface: a model or job of
// another owner is simply not found. Failures throw StorageError (storage_error.hpp); timestamps
// come from the Clock the store was given.
//
// A job's writes after it is accepted are fenced by its attempt number: start_job, save_progress
// and finish_job write only while the store's row is at the attempt the writer holds, so a
// worker that lost the job (it was canceled, deleted, or started again elsewhere) cannot
// overwrite what happened since.

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "server/store/records.hpp"
#include "server/store/subscription.hpp"

namespace meshmark::server {

enum class CancelOutcome { canceled, requested, finished, not_found };

/// The stage of a queued job an idle daemon claimed and is about to start (claim_queued_job).
inline constexpr const char* kClaimedStage = "claimed";

/// What became of a fenced write to a job.
enum class JobWrite {
  written,
  lost,  ///< the job ended, or another attempt holds it: nothing written
  gone,  ///< the job no longer exists (its model was deleted)
};

class Store {
 public:
  virtual ~Store() = default;

  virtual void insert_owner(const OwnerRecord& owner, const std::string& api_key_hash) = 0;
  virtual std::optional<OwnerRecord> owner_by_key_hash(const std::string& api_key_hash) = 0;
  virtual std::vector<OwnerRecord> owners() = 0;  ///< oldest first
  /// The owner's key becomes `api_key_hash` (rotation), or none at all when it is empty
  /// (revocation); the old key stops working at once. False if there is no such owner.
  virtual bool set_api_key(const std::string& owner_id, const std::string& api_key_hash) = 0;

  /// The model and the job that prepares it, in one transaction.
  virtual void insert_model(const ModelRecord& model, const JobRecord& prepare_job) = 0;
  virtual std::optional<ModelRecord> model(const std::string& owner_id, const std::string& model_id) = 0;
  virtual std::optional<ModelRecord> model_by_id(const std::string& model_id) = 0;  ///< for workers
  virtual std::vector<ModelRecord> models(const std::string& owner_id) = 0;
  /// Adds `robust_payload_bits` to the model's report: the payload its carriers keep through
  /// simplification and remeshing (known once it is prepared).
  virtual void set_model_payload_capacity(const std::string& model_id, int bits) = 0;
  /// Removes the model, its embeddings and all its jobs; returns the jobs' ids (their files are
  /// the caller's to remove), nullopt if the model is not found for this owner.
  virtual std::optional<std::vector<std::string>> delete_model(const std::string& owner_id,
                                                               const std::string& model_id) = 0;

  /// The embedding and the job that makes it, in one transaction; false (and nothing stored)
  /// when the model already has an embedding of this payload.
  virtual bool insert_embedding(const EmbeddingRecord& embedding, const JobRecord& embed_job) = 0;
  virtual std::vector<EmbeddingRecord> embeddings(const std::string& model_id) = 0;
  /// Every copy of every model of the owner, oldest first, with its model's name: who received
  /// what, across the library.
  virtual std::vector<HandedOutCopy> owner_embeddings(const std::string& owner_id) = 0;
  /// The owner's jobs of `kind` on the model, oldest first (e.g. its detections).
  virtual std::vector<JobRecord> model_jobs(const std::string& owner_id, const std::string& model_id, JobKind kind) = 0;

  virtual void insert_job(const JobRecord& job) = 0;
  virtual std::optional<JobRecord> job(const std::string& owner_id, const std::string& job_id) = 0;
  virtual std::optional<JobRecord> job_by_id(const std::string& job_id) = 0;  ///< for workers
  /// The job begins attempt `job.attempts` (after start_job in job_transitions.hpp): written only
  /// if the row is unfinished at the attempt before and still held by `job.lease_owner` (a job
  /// another daemon claimed or took over meanwhile is theirs to start).
  virtual JobWrite start_job(const JobRecord& job) = 0;
  /// The running attempt's stage and progress; lost once its cancel was asked for.
  virtual JobWrite save_progress(const JobRecord& job) = 0;
  /// Every way a job ends, in one transaction: its final state, result and error; for a prepare
  /// job its model's state (model_outcome); for an embed job its copy, ready or (never made)
  /// forgotten so that its payload is free again.
  virtual JobWrite finish_job(const JobRecord& job) = 0;
  /// running → queued at the same attempt: the daemon stopped while it ran.
  virtual JobWrite requeue_job(const JobRecord& job) = 0;
  /// Extends to `until` the lease of every unfinished job `owner` holds (its heartbeat).
  virtual void renew_leases(const std::string& owner, const std::string& until) = 0;
  /// Takes every unfinished job whose lease ran out before `now` (and, with `including_own`, the
  /// ones `owner` held in an earlier life: its start after a crash) for `owner` until `until`,
  /// each at most once however many daemons try at the same time. Returns them, oldest first.
  virtual std::vector<JobRecord> take_over_jobs(const std::string& owner, const std::string& now,
                                                const std::string& until, bool including_own) = 0;
  /// Takes for `owner` until `until` the oldest queued job that can run now (a preparation, or a
  /// job whose model is no longer being prepared) and that another daemon holds: an idle daemon's
  /// share of a busy one's queue. One statement, rows other claims hold skipped (SKIP LOCKED), so
  /// no job is taken twice; the holder's own start of it is then fenced (start_job).
  virtual std::optional<JobRecord> claim_queued_job(const std::string& owner, const std::string& until) = 0;
  /// Tells the other daemons watching (watch_claimable_jobs) that this one holds queued jobs it
  /// cannot start yet; nothing where no other daemon shares the store.
  virtual void announce_claimable_jobs() = 0;
  /// Calls `wake` (on a thread of the store's) soon after another daemon announced claimable jobs,
  /// until the subscription is destroyed; nullptr where no other daemon shares the store.
  /// Announcements can be missed (a lost connection): claimers poll as well.
  virtual std::unique_ptr<Subscription> watch_claimable_jobs(std::function<void()> wake) = 0;
  /// A queued job: ended as canceled (finish_job). A running one: its cancel request recorded
  /// (its worker sees it at its next save_progress, which then writes nothing).
  /// Both in one transaction, so the answer never contradicts the store.
  virtual CancelOutcome cancel_job(const std::string& owner_id, const std::string& job_id) = 0;
  /// Jobs in the given states, oldest first (recovery after a restart).
  virtual std::vector<JobRecord> jobs_in_state(JobState state) = 0;
  /// (kind, state) → number of jobs, for metrics.
  virtual std::map<std::pair<std::string, std::string>, long long> job_counts() = 0;

  /// The fingerprint of the master key the store's copies are marked under: `ours` when the store
  /// had none (recorded now, once, even when daemons start at once).
  virtual std::string record_master_key_fingerprint(const std::string& ours) = 0;

  /// A cheap query that proves the store answers (readiness).
  virtual bool healthy() = 0;
};

}  // namespace meshmark::server
