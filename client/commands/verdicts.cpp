#include "client/commands/verdicts.hpp"

#include <cmath>
#include <cstdio>

namespace meshmark::cli {

namespace {

std::string printed(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace

std::string quoted_name(const std::string& name) { return "\"" + name + "\""; }

std::string coincidence_phrase(double log10_p_value) {
  return "chance of coincidence below 1e" + printed("%.0f", std::floor(log10_p_value));
}

std::string nothing_found_phrase(double p_value, double log10_p_value) {
  return "no watermark of this key found (the strongest evidence would occur by chance with probability " +
         (log10_p_value > -3 ? printed("%.3g", p_value) : "1e" + printed("%.0f", std::floor(log10_p_value))) + ")";
}

std::string remote_verdict(const nlohmann::json& result) {
  const nlohmann::json& match = result.value("match", nlohmann::json());
  if (match.is_object())
    return "the copy given to " + quoted_name(match.value("recipient", "")) + " (payload " +
           match.value("payload", "") + "); " + coincidence_phrase(match.value("log10_p_value", 0.0));
  if (result.value("detected", false)) {
    const nlohmann::json& closest = result.value("matches", nlohmann::json::array());
    return "marked with this key, but no copy handed out matches" +
           (closest.empty() ? std::string(" (none was handed out)")
                            : " (the closest, " + quoted_name(closest[0].value("recipient", "")) + ", p " +
                                  printed("%.2g", closest[0].value("p_value", 1.0)) + ")");
  }
  return nothing_found_phrase(result.value("p_value", 1.0), result.value("log10_p_value", 0.0));
}

namespace {

// How the suspect was registered, and a warning when the fit is poor: a reading after a poor fit
// says little either way.
std::string alignment_lines(const nlohmann::json& alignment) {
  std::string out = "  alignment rms " + printed("%.2e", alignment.value("rms", 0.0)) + " of the diagonal" +
                    (alignment.value("non_rigid", false)
                         ? " after unbending (rigid " + printed("%.2e", alignment.value("rigid_rms", 0.0)) + ")"
                         : std::string()) +
                    ", scale " + printed("%.6f", alignment.value("scale", 1.0)) + ", overlap " +
                    printed("%.0f", 100 * alignment.value("overlap", 1.0)) + " %\n";
  if (alignment.value("quality", std::string("good")) == "poor")
    out +=
        "  warning: the suspect fits the original poorly (far from its surface, or much of it off it): "
        "is it this model, or cut from a larger scene? Try the right original, or crop the suspect to the model.\n";
  return out;
}

}  // namespace

std::string remote_evidence(const nlohmann::json& result) {
  const nlohmann::json& ber = result.value("ber", nlohmann::json());
  const nlohmann::json& alignment = result.value("alignment", nlohmann::json::object());
  return "  evidence: " + result.value("evidence", std::string("?")) + "; blind decode " +
         result.value("decoded", std::string()) +
         (result.value("checksum_ok", false) ? " (checksum matches)" : " (checksum fails)") +
         (ber.is_number() ? ", bit error rate " + printed("%.4f", ber.get<double>()) : std::string()) +
         "; correlation " + printed("%.3f", result.value("correlation", 0.0)) + "\n" + alignment_lines(alignment);
}

}  // namespace meshmark::cli
