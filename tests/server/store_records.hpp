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

inline server::JobRecord job_record(const std::string& id, const std::string& owner_id, const std::string& model_id,
                                    JobKind kind) {
  server::JobRecord j;
  j.id = id;
  j.owner_id = owner_id;
  j.model_id = model_id;
  j.kind = kind;
  return j;
}

}  // namespace meshmark::test
