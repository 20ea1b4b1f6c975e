#pragma once
// The plain sentences every detecting command prints first — local detect and trace, and the
// daemon's detections read remotely — so that one answer always reads the same.

#include <nlohmann/json.hpp>
#include <string>

namespace meshmark::cli {

/// A name as the sentences quote it: "partner a".
std::string quoted_name(const std::string& name);
/// "chance of coincidence below 1e-12"
std::string coincidence_phrase(double log10_p_value);
/// "no watermark of this key found (the strongest evidence would occur by chance with probability 0.43)"
std::string nothing_found_phrase(double p_value, double log10_p_value);

/// A daemon's detection (a detect job's result) in one line: whose copy, or marked but no copy
/// matches, or nothing found.
std::string remote_verdict(const nlohmann::json& result);
/// The evidence behind it, as indented lines ending in a newline.
std::string remote_evidence(const nlohmann::json& result);

}  // namespace meshmark::cli
