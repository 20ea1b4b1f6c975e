#pragma once
// The lifecycle words of the API: what a job is for and where it stands, where a model and a
// handed-out copy stand. Written as text only by to_string (the store's columns and the JSON
// bodies use these words) and read back only by the parse functions, which refuse any other.
// The moves between them live in server/store/job_transitions.hpp.

#include <optional>
#include <string>
#include <string_view>

namespace meshmark {

enum class JobKind { prepare, embed, detect };
/// queued → running → succeeded | failed | canceled; running → queued after a restart.
enum class JobState { queued, running, succeeded, failed, canceled };
/// preparing → ready | failed
enum class ModelState { preparing, ready, failed };
/// pending (its embed job runs) → ready; a copy whose job failed is deleted.
enum class EmbeddingState { pending, ready };

std::string to_string(JobKind kind);
std::string to_string(JobState state);
std::string to_string(ModelState state);
std::string to_string(EmbeddingState state);

std::optional<JobKind> parse_job_kind(std::string_view text);
std::optional<JobState> parse_job_state(std::string_view text);
std::optional<ModelState> parse_model_state(std::string_view text);
std::optional<EmbeddingState> parse_embedding_state(std::string_view text);

/// True for the states a job never leaves.
bool is_final(JobState state);

}  // namespace meshmark
