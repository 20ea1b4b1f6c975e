#pragma once
// The daemon's durable records, behind an interface: SQLite is the embedded default; a
// PostgreSQL implementation (several daemons claiming jobs with SELECT … FOR UPDATE SKIP LOCKED)
// is a second implementation of this interface, not a rewrite. Every write is durable when the
// call returns. Owner scoping is part of the interface: a model or job of another owner is
// simply not found. Failures throw StorageError (server/store/storage_error.hpp).

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "server/store/records.hpp"

namespace meshmark::server {

enum class CancelOutcome { canceled, requested, finished, not_found };

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
  virtual void set_model_state(const std::string& model_id, ModelState state, const std::string& error) = 0;
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
  /// The embed job ended: its copy becomes 'ready', or (never made) its record goes and its
  /// payload is free again.
  virtual void finish_embedding(const std::string& embedding_id, bool made) = 0;

  virtual void insert_job(const JobRecord& job) = 0;
  virtual std::optional<JobRecord> job(const std::string& owner_id, const std::string& job_id) = 0;
  virtual std::optional<JobRecord> job_by_id(const std::string& job_id) = 0;  ///< for workers
  /// Writes a job's state, progress, result and error (never its cancel request).
  virtual void update_job(const JobRecord& job) = 0;
  /// A queued job: canceled (with its model, for a prepare job). A running one: its cancel
  /// request recorded. Both in one transaction, so the answer never contradicts the store.
  virtual CancelOutcome cancel_job(const std::string& owner_id, const std::string& job_id, const std::string& now) = 0;
  /// Jobs in the given states, oldest first (recovery after a restart).
  virtual std::vector<JobRecord> jobs_in_state(JobState state) = 0;
  /// (kind, state) → number of jobs, for metrics.
  virtual std::map<std::pair<std::string, std::string>, long long> job_counts() = 0;

  /// A cheap query that proves the store answers (readiness).
  virtual bool healthy() = 0;
};

}  // namespace meshmark::server
