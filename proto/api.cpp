#include "proto/api.hpp"

#include <set>

#include <stdexcept>

#include "core/io/mesh_format.hpp"
#include "core/watermark/payload_code.hpp"
#include "proto/json_text.hpp"

namespace meshmark {

namespace {

std::string string_field(const nlohmann::json& j, const char* key) {
  if (!j.contains(key) || j[key].is_null()) return "";
  if (!j[key].is_string()) throw std::invalid_argument(std::string("'") + key + "' must be a string");
  return j[key].get<std::string>();
}

// Refuses keys outside `known`: a typo must not pass silently, nor bulk be stored.
void check_keys(const nlohmann::json& j, std::initializer_list<const char*> known) {
  for (const auto& [key, value] : j.items()) {
    bool found = false;
    for (const char* k : known) found = found || key == k;
    if (!found) {
      std::string list;
      for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      throw std::invalid_argument("unknown key '" + clip_for_message(key, 40) + "' (known: " + list + ")");
    }
  }
}

// A label: printable UTF-8, at most `max_bytes`.
std::string label_field(const nlohmann::json& j, const char* key, std::size_t max_bytes) {
  std::string value = string_field(j, key);
  if (value.size() > max_bytes)
    throw std::invalid_argument(std::string("'") + key + "' is longer than " + std::to_string(max_bytes) + " bytes");
  if (!is_printable_utf8(value))
    throw std::invalid_argument(std::string("'") + key + "' holds control characters or bidirectional marks");
  return value;
}

}  // namespace

WatermarkOptions parse_watermark_options(const nlohmann::json& j) {
  WatermarkOptions o;
  if (const std::string s = string_field(j, "scheme"); !s.empty()) o.scheme = parse_scheme(s);
  if (const std::string w = string_field(j, "wavelet"); !w.empty()) o.wavelet = parse_wavelet_type(w);
  if (j.contains("strength") && !j["strength"].is_null()) {
    if (!j["strength"].is_number())
      throw std::invalid_argument("'strength' must be a number (percent of the bbox diagonal)");
    o.strength_percent = j["strength"].get<double>();
    if (!strength_in_range(o.strength_percent))
      throw std::invalid_argument("'strength' must be in " + strength_range_text());
  }
  return o;
}

std::vector<EmbedRequest> parse_embed_requests(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("recipients")) return {parse_embed_request(j)};
  if (j.contains("payload") || j.contains("recipient"))
    throw std::invalid_argument("give 'recipients' alone (each copy is assigned its payload), or one 'recipient'");
  const nlohmann::json& names = j["recipients"];
  if (!names.is_array() || names.empty() || names.size() > kMaxBatchRecipients)
    throw std::invalid_argument("'recipients' must be a list of 1 to " + std::to_string(kMaxBatchRecipients) +
                                " names");
  nlohmann::json single = j;
  single.erase("recipients");
  std::vector<EmbedRequest> requests;
  std::set<std::string> seen;
  for (const nlohmann::json& name : names) {
    single["recipient"] = name;
    EmbedRequest r = parse_embed_request(single);
    if (r.recipient.empty()) throw std::invalid_argument("every name in 'recipients' must be a non-empty string");
    if (!seen.insert(r.recipient).second) throw std::invalid_argument("'" + r.recipient + "' is in 'recipients' twice");
    requests.push_back(std::move(r));
  }
  return requests;
}

EmbedRequest parse_embed_request(const nlohmann::json& j) {
  if (!j.is_object()) throw std::invalid_argument("the body must be a JSON object");
  check_keys(j, {"payload", "recipient", "requested_by", "scheme", "wavelet", "strength", "format"});
  EmbedRequest r;
  r.options = parse_watermark_options(j);
  if (const std::string p = string_field(j, "payload"); !p.empty()) {
    const Bits bits = bits_from_hex(p);
    if (bits.size() > static_cast<std::size_t>(kMaxPayloadBits))
      throw std::invalid_argument("the payload has " + std::to_string(bits.size()) + " bits; at most " +
                                  std::to_string(kMaxPayloadBits) + " are accepted");
    r.payload = hex_from_bits(bits);
  }
  r.recipient = label_field(j, "recipient", 200);
  r.requested_by = label_field(j, "requested_by", 200);
  if (!r.payload && r.recipient.empty())
    throw std::invalid_argument("give a 'payload' (hex) or a 'recipient' (the daemon then assigns a payload)");
  r.format = string_field(j, "format");
  if (!r.format.empty() && !parse_mesh_format(r.format))
    throw std::invalid_argument("'format' must be one of " + known_mesh_formats());
  return r;
}

nlohmann::json embed_request_json(const EmbedRequest& r) {
  nlohmann::json j = {{"scheme", to_string(r.options.scheme)},
                      {"wavelet", to_string(r.options.wavelet)},
                      {"strength", r.options.strength_percent}};
  if (r.payload) j["payload"] = *r.payload;
  if (!r.recipient.empty()) j["recipient"] = r.recipient;
  if (!r.requested_by.empty()) j["requested_by"] = r.requested_by;
  if (!r.format.empty()) j["format"] = r.format;
  return j;
}

OwnerRequest parse_owner_request(const nlohmann::json& j) {
  if (!j.is_object()) throw std::invalid_argument("the body must be a JSON object, e.g. {\"name\": \"Studio A\"}");
  check_keys(j, {"name"});
  OwnerRequest r;
  if (j.contains("name")) {
    r.name = label_field(j, "name", 200);
    if (r.name.empty()) throw std::invalid_argument("'name' must not be empty");
  }
  return r;
}

DetectRequest parse_detect_query(const std::string& scheme, const std::string& wavelet, const std::string& bits) {
  DetectRequest r;
  r.settings_given = !scheme.empty() || !wavelet.empty() || !bits.empty();
  nlohmann::json j = nlohmann::json::object();
  if (!scheme.empty()) j["scheme"] = scheme;
  if (!wavelet.empty()) j["wavelet"] = wavelet;
  r.options = parse_watermark_options(j);
  if (!bits.empty()) {
    try {
      std::size_t used = 0;
      r.bits = std::stoi(bits, &used);
      if (used != bits.size()) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw std::invalid_argument("'bits' must be a whole number");
    }
    if (r.bits <= 0 || r.bits % 4 != 0 || r.bits > kMaxPayloadBits)
      throw std::invalid_argument("'bits' must be a multiple of 4 between 4 and " + std::to_string(kMaxPayloadBits));
  }
  return r;
}

}  // namespace meshmark
