#include "proto/api.hpp"

#include <stdexcept>

#include "core/io/mesh_format.hpp"
#include "core/watermark/payload_code.hpp"

namespace meshmark {

namespace {

std::string string_field(const nlohmann::json& j, const char* key) {
  if (!j.contains(key) || j[key].is_null()) return "";
  if (!j[key].is_string()) throw std::invalid_argument(std::string("'") + key + "' must be a string");
  return j[key].get<std::string>();
}

}  // namespace

WatermarkOptions parse_watermark_options(const nlohmann::json& j) {
  WatermarkOptions o;
  if (const std::string s = string_field(j, "scheme"); !s.empty()) o.scheme = parse_scheme(s);
  if (const std::string w = string_field(j, "wavelet"); !w.empty()) o.wavelet = parse_wavelet_type(w);
  if (j.contains("strength") && !j["strength"].is_null()) {
    if (!j["strength"].is_number()) throw std::invalid_argument("'strength' must be a number (percent of the bbox diagonal)");
    o.strength_percent = j["strength"].get<double>();
    if (!(o.strength_percent > 0 && o.strength_percent <= 5))
      throw std::invalid_argument("'strength' must be in (0, 5] percent of the bounding-box diagonal");
  }
  return o;
}

EmbedRequest parse_embed_request(const nlohmann::json& j) {
  if (!j.is_object()) throw std::invalid_argument("the body must be a JSON object");
  EmbedRequest r;
  r.options = parse_watermark_options(j);
  if (const std::string p = string_field(j, "payload"); !p.empty()) {
    const Bits bits = bits_from_hex(p);
    if (bits.size() > static_cast<std::size_t>(kMaxPayloadBits))
      throw std::invalid_argument("the payload has " + std::to_string(bits.size()) + " bits; at most " +
                                  std::to_string(kMaxPayloadBits) + " are accepted");
    r.payload = hex_from_bits(bits);
  }
  r.recipient = string_field(j, "recipient");
  if (r.recipient.size() > 200) throw std::invalid_argument("'recipient' is longer than 200 characters");
  if (!r.payload && r.recipient.empty())
    throw std::invalid_argument("give a 'payload' (hex) or a 'recipient' (the daemon then assigns a payload)");
  r.format = string_field(j, "format");
  if (!r.format.empty() && !parse_mesh_format(r.format))
    throw std::invalid_argument("'format' must be obj, off, ply or stl");
  return r;
}

DetectRequest parse_detect_query(const std::string& scheme, const std::string& wavelet, const std::string& bits) {
  DetectRequest r;
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
