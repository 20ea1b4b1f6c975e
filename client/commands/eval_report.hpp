#pragma once
// The evaluation's tables, as Markdown (for the results pages in docs/) and JSON.

#include <nlohmann/json.hpp>
#include <string>

#include "core/evaluation/evaluate.hpp"

namespace meshmark::cli {

std::string eval_markdown(const EvalResults& results, const std::string& command);
nlohmann::json eval_json(const EvalResults& results, const std::string& command);

}  // namespace meshmark::cli
