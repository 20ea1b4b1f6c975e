#pragma once
// The evidence report of a detection: one self-contained HTML file (its pictures inline, no
// script) that a licensing team can attach to a takedown notice: the verdict in a sentence, the
// statistics and how to read them, the aligned pictures, the copy's record and the digests.

#include <optional>
#include <string>
#include <vector>

#include "core/render/alignment_pictures.hpp"
#include "server/store/records.hpp"

namespace meshmark::server {

struct EvidenceReport {
  ModelRecord model;
  JobRecord detection;                  ///< a succeeded detect job
  std::optional<EmbeddingRecord> copy;  ///< the copy it named, if any
  std::string original_sha256;          ///< of the model's file as uploaded
  std::string suspect_sha256;           ///< of the suspect's file as uploaded
  std::vector<Picture> pictures;
  std::string generated_at, software;
};

/// The verdict in one plain sentence (what the console shows above the evidence, too).
std::string verdict_sentence(const EvidenceReport& report);

std::string evidence_report_html(const EvidenceReport& report);

/// Text made safe to put in HTML (element content and quoted attributes).
std::string html_escape(const std::string& text);

}  // namespace meshmark::server
