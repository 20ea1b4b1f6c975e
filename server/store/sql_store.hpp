#pragma once
// The Store written once over any SQL database (sql_database.hpp): SQLite for one daemon,
// PostgreSQL for several. Every statement is plain SQL both engines read the same way.

#include <memory>

#include "server/clock.hpp"
#include "server/store/sql_database.hpp"
#include "server/store/store.hpp"

namespace meshmark::server {

class SqlStore : public Store {
 public:
  SqlStore(std::unique_ptr<sql::Database> database, const Clock& clock);

  void insert_owner(const OwnerRecord& owner, const std::string& api_key_hash) override;
  std::optional<OwnerRecord> owner_by_key_hash(const std::string& api_key_hash) override;
  std::vector<OwnerRecord> owners() override;
  bool set_api_key(const std::string& owner_id, const std::string& api_key_hash) override;
  void insert_model(const ModelRecord& model, const JobRecord& prepare_job) override;
  std::optional<ModelRecord> model(const std::string& owner_id, const std::string& model_id) override;
  std::optional<ModelRecord> model_by_id(const std::string& model_id) override;
  std::vector<ModelRecord> models(const std::string& owner_id) override;
  void set_model_payload_capacity(const std::string& model_id, int bits) override;
  std::optional<std::vector<std::string>> delete_model(const std::string& owner_id,
                                                       const std::string& model_id) override;
  bool insert_embedding(const EmbeddingRecord& embedding, const JobRecord& embed_job) override;
  std::vector<EmbeddingRecord> embeddings(const std::string& model_id) override;
  std::vector<HandedOutCopy> owner_embeddings(const std::string& owner_id) override;
  std::vector<JobRecord> model_jobs(const std::string& owner_id, const std::string& model_id, JobKind kind) override;
  void insert_job(const JobRecord& job) override;
  std::optional<JobRecord> job(const std::string& owner_id, const std::string& job_id) override;
  std::optional<JobRecord> job_by_id(const std::string& job_id) override;
  JobWrite start_job(const JobRecord& job) override;
  JobWrite save_progress(const JobRecord& job) override;
  JobWrite finish_job(const JobRecord& job) override;
  JobWrite requeue_job(const JobRecord& job) override;
  void renew_leases(const std::string& owner, const std::string& until) override;
  std::vector<JobRecord> take_over_jobs(const std::string& owner, const std::string& now, const std::string& until,
                                        bool including_own) override;
  std::optional<JobRecord> claim_queued_job(const std::string& owner, const std::string& until) override;
  void announce_claimable_jobs() override;
  std::unique_ptr<Subscription> watch_claimable_jobs(std::function<void()> wake) override;
  CancelOutcome cancel_job(const std::string& owner_id, const std::string& job_id) override;
  std::vector<JobRecord> jobs_in_state(JobState state) override;
  std::map<std::pair<std::string, std::string>, long long> job_counts() override;
  std::string record_master_key_fingerprint(const std::string& ours) override;
  bool healthy() override;

 private:
  // A fenced write to one job, on its own.
  JobWrite write_job(const std::string& statement, const sql::Params& params, const std::string& job_id);

  std::unique_ptr<sql::Database> database_;
  const Clock& clock_;
};

}  // namespace meshmark::server
