#pragma once
// The embedded store: one SQLite database in WAL mode with synchronous=FULL, foreign keys on.
// One connection behind a mutex: every statement is short, and SQLite serializes writers anyway.

#include <filesystem>
#include <mutex>

#include "server/clock.hpp"
#include "server/store/store.hpp"

struct sqlite3;

namespace meshmark::server {

class SqliteStore : public Store {
 public:
  /// Opens (creating if needed) the database file and brings its schema up to date
  /// (sqlite_schema.hpp). Throws StorageError, or std::runtime_error for a newer schema.
  explicit SqliteStore(const std::filesystem::path& file, const Clock& clock = system_clock());
  ~SqliteStore() override;
  SqliteStore(const SqliteStore&) = delete;
  SqliteStore& operator=(const SqliteStore&) = delete;

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
  void insert_job(const JobRecord& job) override;
  std::optional<JobRecord> job(const std::string& owner_id, const std::string& job_id) override;
  std::optional<JobRecord> job_by_id(const std::string& job_id) override;
  JobWrite start_job(const JobRecord& job) override;
  JobWrite save_progress(const JobRecord& job) override;
  JobWrite finish_job(const JobRecord& job) override;
  JobWrite requeue_job(const JobRecord& job) override;
  CancelOutcome cancel_job(const std::string& owner_id, const std::string& job_id) override;
  std::vector<JobRecord> jobs_in_state(JobState state) override;
  std::map<std::pair<std::string, std::string>, long long> job_counts() override;
  std::string record_master_key_fingerprint(const std::string& ours) override;
  bool healthy() override;

 private:
  // The caller holds mutex_.
  void insert_job_locked(const JobRecord& job);
  JobWrite finish_job_locked(const JobRecord& job);
  JobWrite written_or_why(const std::string& job_id);  // after a fenced UPDATE

  const Clock& clock_;
  std::mutex mutex_;
  sqlite3* db_ = nullptr;
};

}  // namespace meshmark::server
