#pragma once
// What the daemon keeps: owners, models, embeddings, jobs.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "proto/job_specs.hpp"
#include "proto/states.hpp"

namespace meshmark::server {

struct OwnerRecord {
  std::string id;
  std::string name;
  std::string created_at;
  bool key_active = true;  ///< false once the admin revoked its key
};

struct ModelRecord {
  std::string id, owner_id, name, format;
  ModelState state = ModelState::preparing;
  std::string error;
  nlohmann::json report;  ///< the validation report
  long long vertices = 0, faces = 0;
  std::string digest;
  std::string created_at, updated_at;
};

/// One watermarked copy handed out: which payload went to whom, with which parameters.
struct EmbeddingRecord {
  std::string id, model_id, owner_id, payload, recipient, job_id;
  nlohmann::json parameters;
  std::string created_at;
  EmbeddingState state = EmbeddingState::pending;
  std::string requested_by = {};  ///< who asked for the copy (a label the caller gave; empty: not said)
};

/// A copy with the name of the model it was made of (an export's row).
struct HandedOutCopy {
  EmbeddingRecord copy;
  std::string model_name;
};

/// Its moves between states: server/jobs/job_transitions.hpp.
struct JobRecord {
  std::string id, owner_id, model_id;
  JobSpec spec = PrepareJobSpec{};  ///< what it is asked to do (its kind follows)
  JobState state = JobState::queued;
  double progress = 0;
  std::string stage;
  nlohmann::json result;  ///< null until succeeded
  std::string error;
  int attempts = 0;  ///< starts so far; the current one fences every write (Store::finish_job)
  std::string created_at, started_at, finished_at;
  bool cancel_requested = false;  ///< asked to stop while it ran (survives a restart)
  /// The daemon that holds the job (queued in its memory or running there), until a time it
  /// keeps renewing; a job whose lease ran out is taken over by another (Store::take_over_jobs).
  std::string lease_owner, lease_until;

  JobKind kind() const { return job_kind(spec); }
  bool finished() const { return is_final(state); }
};

}  // namespace meshmark::server
