#pragma once
// The JSON views of the API's resources, with their links.

#include <nlohmann/json.hpp>

#include "server/store/records.hpp"

namespace meshmark::server {

/// Where a model's record keeps its shape signature (in its report; not shown in its view).
inline constexpr const char* kShapeSignatureKey = "shape_signature";

/// With `preparation` (the job preparing a model that is still preparing): its state and progress.
nlohmann::json model_view(const ModelRecord& model, const JobRecord* preparation = nullptr);
nlohmann::json job_view(const JobRecord& job);
nlohmann::json embedding_view(const EmbeddingRecord& embedding);
/// A copy in the export of every copy handed out: its view with its model's id and name.
nlohmann::json handed_out_view(const HandedOutCopy& h);
/// A detect job in a model's history: when, its state, and its verdict (the copy it names).
nlohmann::json detection_view(const JobRecord& job);

}  // namespace meshmark::server
