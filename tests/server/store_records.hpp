#pragma once
// Records for store-level tests: an owner's model being prepared, and a job on it.

#include <string>

#include "server/store/records.hpp"

namespace meshmark::test {

inline server::ModelRecord preparing_model(const std::string& id, const std::string& owner_id) {
  server::ModelRecord m;
  m.id = id;
  m.owner_id = owner_id;
  m.state = ModelState::preparing;
  m.report = nlohmann::json::object();
  return m;
}

/// A spec of the kind, as a handler would write it; an embed job's copy is `embedding_id`.
inline JobSpec job_spec(JobKind kind, const std::string& embedding_id = "emb_1") {
  switch (kind) {
    case JobKind::embed:
      return EmbedJobSpec{parse_embed_request({{"recipient", "shop"}}), embedding_id, "ply", "ab"};
    case JobKind::detect:
      return DetectJobSpec{parse_detect_query("", "", ""), 1000};
    case JobKind::prepare:
      break;
  }
  return PrepareJobSpec{};
}

inline server::JobRecord job_record(const std::string& id, const std::string& owner_id, const std::string& model_id,
                                    JobKind kind) {
  server::JobRecord j;
  j.id = id;
  j.owner_id = owner_id;
  j.model_id = model_id;
  j.spec = job_spec(kind);
  return j;
}

}  // namespace meshmark::test
