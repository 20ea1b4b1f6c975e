#pragma once
// Request and response bodies of the HTTP API, shared by the daemon and the client. Parsing
// throws std::invalid_argument with a message fit for a 400 problem's detail.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/watermark/watermark_options.hpp"

namespace meshmark {

/// {"scheme": "spread"|"paper", "wavelet": ..., "strength": percent} — every key optional.
WatermarkOptions parse_watermark_options(const nlohmann::json& j);

struct EmbedRequest {
  std::optional<std::string> payload;  ///< hex; absent: the daemon assigns one unique within the model
  std::string recipient;               ///< who receives this copy (a label); required when no payload
  std::string requested_by;            ///< who asked for it (a label the caller gives; empty: not said)
  WatermarkOptions options;
  std::string format;  ///< of the watermarked file; empty: the model's (kept whole); obj, off, ply, stl: the marked
                       ///< surface only
};
/// Refuses keys it does not know and values of the wrong type or range.
EmbedRequest parse_embed_request(const nlohmann::json& j);
/// A batch asks for one copy per name in "recipients" (each assigned its own payload), with the
/// same settings; a request without "recipients" is one copy (parse_embed_request).
inline constexpr std::size_t kMaxBatchRecipients = 256;
std::vector<EmbedRequest> parse_embed_requests(const nlohmann::json& j);
/// The request as parse_embed_request reads it back: only what it means, normalized.
nlohmann::json embed_request_json(const EmbedRequest& request);

/// POST /v1/owners: {"name": "Studio A"} (optional; printable UTF-8, at most 200 bytes).
struct OwnerRequest {
  std::string name = "owner";
};
OwnerRequest parse_owner_request(const nlohmann::json& j);

struct DetectRequest {
  WatermarkOptions options;
  int bits = 64;
  /// Whether any of scheme, wavelet and bits was given: only then are these settings read besides
  /// the settings of each copy made (the defaults alone are not a request).
  bool settings_given = false;
};
DetectRequest parse_detect_query(const std::string& scheme, const std::string& wavelet, const std::string& bits);

/// The largest payload the API accepts, in bits.
inline constexpr int kMaxPayloadBits = 256;

}  // namespace meshmark
