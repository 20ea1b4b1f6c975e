#include "proto/job_specs.hpp"

#include <stdexcept>

namespace meshmark {

namespace {

std::string text_of(const nlohmann::json& j, const char* key) {
  if (!j.contains(key) || !j.at(key).is_string())
    throw std::invalid_argument(std::string("a job spec without its '") + key + "'");
  return j.at(key).get<std::string>();
}

nlohmann::json versioned(nlohmann::json j) {
  j["version"] = kJobSpecVersion;
  return j;
}

nlohmann::json spec_json(const PrepareJobSpec&) { return versioned(nlohmann::json::object()); }

nlohmann::json spec_json(const EmbedJobSpec& s) {
  return versioned({{"request", embed_request_json(s.request)},
                    {"embedding_id", s.embedding_id},
                    {"output_format", s.output_format},
                    {"assigned_payload", s.assigned_payload}});
}

nlohmann::json spec_json(const DetectJobSpec& s) {
  return versioned({{"scheme", to_string(s.request.options.scheme)},
                    {"wavelet", to_string(s.request.options.wavelet)},
                    {"bits", s.request.bits},
                    {"settings_given", s.request.settings_given},
                    {"suspect_vertices", s.suspect_vertices},
                    {"suspect_sha256", s.suspect_sha256}});
}

EmbedJobSpec parse_embed_spec(const nlohmann::json& j) {
  if (!j.contains("request")) throw std::invalid_argument("an embed job spec without its request");
  return {parse_embed_request(j.at("request")), text_of(j, "embedding_id"), text_of(j, "output_format"),
          text_of(j, "assigned_payload")};
}

DetectJobSpec parse_detect_spec(const nlohmann::json& j) {
  if (!j.contains("bits") || !j.at("bits").is_number_integer())
    throw std::invalid_argument("a detect job spec without its bits");
  DetectJobSpec s;
  s.request = parse_detect_query(text_of(j, "scheme"), text_of(j, "wavelet"), std::to_string(j.at("bits").get<int>()));
  s.request.settings_given = j.value("settings_given", true);
  s.suspect_vertices = j.value("suspect_vertices", 0LL);
  s.suspect_sha256 = j.value("suspect_sha256", std::string());
  return s;
}

}  // namespace

JobKind job_kind(const JobSpec& spec) {
  return std::visit(
      [](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, PrepareJobSpec>) return JobKind::prepare;
        if constexpr (std::is_same_v<S, EmbedJobSpec>) return JobKind::embed;
        return JobKind::detect;
      },
      spec);
}

nlohmann::json job_spec_json(const JobSpec& spec) {
  return std::visit([](const auto& s) { return spec_json(s); }, spec);
}

JobSpec parse_job_spec(JobKind kind, const nlohmann::json& j) {
  if (!j.is_object() || j.value("version", 0) != kJobSpecVersion)
    throw std::invalid_argument("a job spec of version " +
                                (j.is_object() ? j.value("version", nlohmann::json(0)).dump() : "?") +
                                "; this daemon reads version " + std::to_string(kJobSpecVersion));
  switch (kind) {
    case JobKind::prepare:
      return PrepareJobSpec{};
    case JobKind::embed:
      return parse_embed_spec(j);
    case JobKind::detect:
      return parse_detect_spec(j);
  }
  throw std::invalid_argument("a job spec of an unknown kind");
}

nlohmann::json upgrade_job_spec(JobKind kind, const nlohmann::json& stored) {
  if (stored.is_object() && stored.contains("version")) return stored;
  nlohmann::json j = stored.is_object() ? stored : nlohmann::json::object();
  if (kind == JobKind::embed && !j.contains("request")) {
    // The first embed jobs kept the client's request flat beside the daemon's own keys.
    nlohmann::json asked = j;
    for (const char* daemon_key : {"embedding_id", "output_format", "assigned_payload"}) asked.erase(daemon_key);
    j = {{"request", asked},
         {"embedding_id", j.value("embedding_id", "")},
         {"output_format", j.value("output_format", "")},
         {"assigned_payload", j.value("assigned_payload", "")}};
  }
  return versioned(j);
}

}  // namespace meshmark
