#pragma once
// What a job is asked to do, typed and versioned: written by the handler that accepts the
// request, stored with the job, read by the worker that runs it (perhaps another daemon, perhaps
// a newer one). A new field or meaning is a new version; a store holding older versions is
// upgraded by a migration (upgrade_job_spec), so the runner reads one shape only.

#include <nlohmann/json.hpp>
#include <string>
#include <variant>

#include "proto/api.hpp"
#include "proto/states.hpp"

namespace meshmark {

inline constexpr int kJobSpecVersion = 1;

/// Prepare the model's original (parameterization, grid, carriers).
struct PrepareJobSpec {};

/// Write one marked copy for a recipient.
struct EmbedJobSpec {
  EmbedRequest request;          ///< as the client asked, normalized
  std::string embedding_id;      ///< the copy's record, pending until the job succeeds
  std::string output_format;     ///< the copy's format (the model's when the client named none)
  std::string assigned_payload;  ///< hex: the client's payload or one the daemon assigned
};

/// Read a suspect (stored beside the job) and name the copy it came from.
struct DetectJobSpec {
  DetectJobSpec() = default;
  DetectJobSpec(DetectRequest request, long long suspect_vertices, std::string suspect_sha256 = {})
      : request(request), suspect_vertices(suspect_vertices), suspect_sha256(std::move(suspect_sha256)) {}
  DetectRequest request;
  long long suspect_vertices = 0;  ///< what the job's memory is reserved for
  std::string suspect_sha256;      ///< of the file as uploaded (hex; empty for jobs of older versions)
};

using JobSpec = std::variant<PrepareJobSpec, EmbedJobSpec, DetectJobSpec>;

JobKind job_kind(const JobSpec& spec);
/// {"version": kJobSpecVersion, …}
nlohmann::json job_spec_json(const JobSpec& spec);
/// Throws std::invalid_argument for another version or a shape that does not fit `kind`.
JobSpec parse_job_spec(JobKind kind, const nlohmann::json& j);
/// A spec as stored by any earlier version (none before 1: the requests before typed specs, flat
/// or nested), as the current version's JSON.
nlohmann::json upgrade_job_spec(JobKind kind, const nlohmann::json& stored);

}  // namespace meshmark
