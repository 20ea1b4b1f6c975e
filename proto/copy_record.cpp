#include "proto/copy_record.hpp"

#include <stdexcept>

namespace meshmark {

namespace {

std::string text(const nlohmann::json& j, const char* key) {
  if (!j.contains(key) || !j[key].is_string())
    throw std::invalid_argument(std::string("the record has no '") + key + "'");
  return j[key].get<std::string>();
}

}  // namespace

nlohmann::json to_json(const CopyRecord& r) {
  nlohmann::json j = {{"meshmark_record", kCopyRecordVersion},
                      {"payload", r.payload},
                      {"payload_bits", 4 * r.payload.size()},
                      {"scheme", r.scheme},
                      {"wavelet", r.wavelet},
                      {"base", r.base},
                      {"strength", r.strength},
                      {"original",
                       {{"digest", r.original_digest},
                        {"vertices", r.original_vertices},
                        {"faces", r.original_faces},
                        {"file", r.original_file},
                        {"stored", r.stored_original},
                        {"prepared", r.stored_prepared}}},
                      {"copy", r.copy_file},
                      {"verified", r.verified},
                      {"created_at", r.created_at}};
  if (!r.recipient.empty()) j["recipient"] = r.recipient;
  return j;
}

CopyRecord copy_record_from_json(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("meshmark_record")) throw std::invalid_argument("not a meshmark copy record");
  if (!j["meshmark_record"].is_number_integer() || j["meshmark_record"].get<int>() > kCopyRecordVersion)
    throw std::invalid_argument("a copy record of a newer meshmark (version " + j["meshmark_record"].dump() + ")");
  CopyRecord r;
  r.payload = text(j, "payload");
  r.scheme = text(j, "scheme");
  r.wavelet = text(j, "wavelet");
  r.base = text(j, "base");
  if (!j.contains("strength") || !j["strength"].is_number())
    throw std::invalid_argument("the record has no 'strength'");
  r.strength = j["strength"].get<double>();
  if (!j.contains("original") || !j["original"].is_object())
    throw std::invalid_argument("the record has no 'original'");
  const nlohmann::json& o = j["original"];
  r.original_digest = text(o, "digest");
  r.original_vertices = o.value("vertices", 0LL);
  r.original_faces = o.value("faces", 0LL);
  r.original_file = o.value("file", "");
  r.stored_original = o.value("stored", "");
  r.stored_prepared = o.value("prepared", "");
  for (const std::string* name : {&r.stored_original, &r.stored_prepared})
    if (name->find('/') != std::string::npos || *name == "." || *name == "..")
      throw std::invalid_argument("the record's stored files must lie beside it: " + *name);
  r.copy_file = j.value("copy", "");
  r.created_at = j.value("created_at", "");
  r.verified = j.value("verified", true);
  r.recipient = j.value("recipient", "");
  return r;
}

}  // namespace meshmark
