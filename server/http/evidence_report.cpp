#include "server/http/evidence_report.hpp"

#include <cmath>
#include <sstream>

#include "core/io/base64.hpp"

namespace meshmark::server {

namespace {

const char* kStyle =
    "body{font-family:system-ui,sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;color:#222}"
    "h1{font-size:1.5rem}.verdict{font-size:1.2rem;padding:1rem;border-left:6px solid #c60;background:#fdf3ea}"
    ".verdict.none{border-color:#888;background:#f3f3f3}table{border-collapse:collapse;margin:.5rem 0}"
    "td,th{border:1px solid #ccc;padding:.3rem .6rem;text-align:left;vertical-align:top}"
    "code{word-break:break-all}figure{display:inline-block;margin:.5rem;width:22rem}"
    "figure img{width:100%;border:1px solid #ccc}figcaption{font-size:.9rem;color:#555}";

// "1 in 10^N" for a p-value given as its log10; plain for moderate values.
std::string chance(double log10_p) {
  if (!std::isfinite(log10_p)) return "not computed";
  if (log10_p > -4) {
    std::ostringstream s;
    s.precision(3);
    s << std::pow(10.0, log10_p);
    return s.str();
  }
  return "below 1 in 10^" + std::to_string(static_cast<long long>(std::floor(-log10_p)));
}

std::string number(const nlohmann::json& j, const char* key) {
  if (!j.contains(key) || j.at(key).is_null()) return "—";
  return j.at(key).dump();
}

void row(std::ostringstream& out, const std::string& name, const std::string& value) {
  out << "<tr><th>" << html_escape(name) << "</th><td>" << html_escape(value) << "</td></tr>\n";
}

void statistics(std::ostringstream& out, const nlohmann::json& r) {
  const nlohmann::json alignment = r.value("alignment", nlohmann::json::object());
  out << "<h2>The statistics</h2><table>\n";
  row(out, "Mark found", r.value("detected", false) ? "yes" : "no");
  row(out, "Payload read", r.value("decoded", std::string("—")));
  const nlohmann::json match = r.contains("match") && r.at("match").is_object() ? r.at("match") : nlohmann::json();
  if (match.is_object())
    row(out, "Bits read wrong, of the named copy's payload", number(match, "bit_errors") + " of " + number(r, "bits"));
  else row(out, "Bits read", number(r, "bits"));
  row(out, "Chance of coincidence (p-value)", chance(r.value("log10_p_value", 0.0)));
  row(out, "log10 of the p-value", number(r, "log10_p_value"));
  row(out, "Alignment quality / overlap / residual (of the diagonal)",
      alignment.value("quality", std::string("—")) + " / " + number(alignment, "overlap") + " / " +
          number(alignment, "rms"));
  row(out, "Alignment: bent copy unbent", alignment.value("non_rigid", false) ? "yes" : "no");
  out << "</table>\n"
      << "<p>How to read them: the detector compares the suspect, aligned to the original, with the "
         "original and reads the keyed pattern each copy carries. The p-value is the probability that a "
         "mesh carrying no copy of this model, or another recipient's copy, reads as closely as this "
         "suspect did: the smaller, the stronger the evidence. The bits read wrong are the named "
         "copy's payload bits the detector read otherwise (0: the recipient's number was read exactly). A poor "
         "alignment "
         "means the suspect is not mostly the original's shape.</p>\n";
}

void record(std::ostringstream& out, const EvidenceReport& report) {
  out << "<h2>The records</h2><table>\n";
  row(out, "Model", report.model.name + " (" + report.model.id + ", uploaded " + report.model.created_at + ")");
  if (report.copy) {
    row(out, "Copy handed out to", report.copy->recipient.empty() ? "(no recipient named)" : report.copy->recipient);
    row(out, "Copy asked for by", report.copy->requested_by.empty() ? "(not recorded)" : report.copy->requested_by);
    row(out, "Copy made", report.copy->created_at);
    row(out, "Copy's payload", report.copy->payload);
    row(out, "Copy's settings", report.copy->parameters.dump());
  }
  row(out, "Detection",
      report.detection.id + ", asked " + report.detection.created_at + ", finished " + report.detection.finished_at);
  row(out, "SHA-256 of the original's file", report.original_sha256.empty() ? "—" : report.original_sha256);
  row(out, "Shape digest of the original", report.model.digest);
  row(out, "SHA-256 of the suspect's file", report.suspect_sha256.empty() ? "—" : report.suspect_sha256);
  row(out, "Report made", report.generated_at + " by " + report.software);
  out << "</table>\n";
}

}  // namespace

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string verdict_sentence(const EvidenceReport& report) {
  const nlohmann::json& r = report.detection.result;
  const std::string model = "\u201c" + report.model.name + "\u201d";
  const std::string odds = chance(r.value("log10_p_value", 0.0));
  if (report.copy) {
    const nlohmann::json match = r.value("match", nlohmann::json::object());
    const std::string who = report.copy->recipient.empty() ? "payload " + report.copy->payload : report.copy->recipient;
    return "This suspect is the copy of " + model + " handed out to " + who + " on " + report.copy->created_at +
           "; the chance that this is a coincidence is " + chance(match.value("log10_p_value", 0.0)) + ".";
  }
  if (r.value("detected", false))
    return "This suspect carries the owner's mark on " + model + " (chance of coincidence " + odds +
           "), but its payload matches no copy recorded as handed out.";
  return "No mark was found: this suspect is not shown to be a copy of " + model + " (chance of coincidence " + odds +
         ").";
}

std::string evidence_report_html(const EvidenceReport& report) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>Evidence report: "
      << html_escape(report.model.name) << "</title>\n<style>" << kStyle << "</style></head><body>\n"
      << "<h1>Watermark evidence report</h1>\n<p class=\"verdict" << (report.copy ? "" : " none") << "\">"
      << html_escape(verdict_sentence(report)) << "</p>\n";
  statistics(out, report.detection.result);
  out << "<h2>The suspect aligned to the original</h2>\n";
  for (const Picture& p : report.pictures)
    out << "<figure><img alt=\"" << html_escape(p.caption) << "\" src=\"data:image/png;base64," << base64_encode(p.png)
        << "\"><figcaption>" << html_escape(p.caption) << "</figcaption></figure>\n";
  record(out, report);
  out << "</body></html>\n";
  return out.str();
}

}  // namespace meshmark::server
