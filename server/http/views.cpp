#include "server/http/views.hpp"

#include "proto/links.hpp"

namespace meshmark::server {

nlohmann::json model_view(const ModelRecord& m, const JobRecord* preparation) {
  nlohmann::json j = {{"id", m.id},
                      {"name", m.name},
                      {"format", m.format},
                      {"state", to_string(m.state)},
                      {"vertices", m.vertices},
                      {"faces", m.faces},
                      {"digest", m.digest},
                      {"report", m.report},
                      {"created_at", m.created_at},
                      {"updated_at", m.updated_at},
                      {"links",
                       {{"self", links::model(m.id)},
                        {"embed", links::model_embed(m.id)},
                        {"detect", links::model_detect(m.id)},
                        {"embeddings", links::model_embeddings(m.id)},
                        {"detections", links::model_detections(m.id)},
                        {"preview", links::model_preview(m.id)}}}};
  if (!m.error.empty()) j["error"] = m.error;
  if (j["report"].is_object()) j["report"].erase(kShapeSignatureKey);
  if (preparation && m.state == ModelState::preparing) {
    j["preparation"] = {{"job_id", preparation->id},
                        {"state", to_string(preparation->state)},
                        {"progress", preparation->progress},
                        {"stage", preparation->stage}};
    j["links"]["preparation"] = links::job(preparation->id);
  }
  return j;
}

nlohmann::json job_view(const JobRecord& j) {
  nlohmann::json v = {{"id", j.id},
                      {"kind", to_string(j.kind())},
                      {"state", to_string(j.state)},
                      {"progress", j.progress},
                      {"stage", j.stage},
                      {"attempts", j.attempts},
                      {"model_id", j.model_id},
                      {"created_at", j.created_at},
                      {"links", {{"self", links::job(j.id)}}}};
  if (!j.started_at.empty()) v["started_at"] = j.started_at;
  if (!j.finished_at.empty()) v["finished_at"] = j.finished_at;
  if (j.state == JobState::succeeded) v["result"] = j.result;
  if (j.state == JobState::failed || j.state == JobState::canceled) v["error"] = j.error;
  if (j.state == JobState::succeeded && j.kind() == JobKind::embed) v["links"]["result"] = links::job_result(j.id);
  if (j.state == JobState::succeeded && j.kind() != JobKind::prepare) v["links"]["preview"] = links::job_preview(j.id);
  if (j.state == JobState::succeeded && j.kind() == JobKind::detect) v["links"]["report"] = links::job_report(j.id);
  return v;
}

nlohmann::json embedding_view(const EmbeddingRecord& e) {
  return {{"id", e.id},
          {"payload", e.payload},
          {"recipient", e.recipient},
          {"requested_by", e.requested_by},
          {"job_id", e.job_id},
          {"state", to_string(e.state)},
          {"parameters", e.parameters},
          {"created_at", e.created_at}};
}

nlohmann::json handed_out_view(const HandedOutCopy& h) {
  nlohmann::json v = embedding_view(h.copy);
  v["model_id"] = h.copy.model_id;
  v["model_name"] = h.model_name;
  return v;
}

nlohmann::json detection_view(const JobRecord& j) {
  nlohmann::json v = {{"job_id", j.id},
                      {"state", to_string(j.state)},
                      {"created_at", j.created_at},
                      {"finished_at", j.finished_at},
                      {"links", {{"job", links::job(j.id)}}}};
  if (j.state == JobState::succeeded) {
    v["detected"] = j.result.value("detected", false);
    v["log10_p_value"] = j.result.value("log10_p_value", 0.0);
    v["match"] = j.result.value("match", nlohmann::json());
  }
  if (j.state == JobState::failed) v["error"] = j.error;
  return v;
}

}  // namespace meshmark::server
