#pragma once
// The JSON views of the API's resources, with their links.

#include <nlohmann/json.hpp>

#include "server/store/records.hpp"

namespace meshmark::server {

nlohmann::json model_view(const ModelRecord& model);
nlohmann::json job_view(const JobRecord& job);
nlohmann::json embedding_view(const EmbeddingRecord& embedding);

}  // namespace meshmark::server
