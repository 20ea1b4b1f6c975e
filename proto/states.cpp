#include "proto/states.hpp"

#include <array>
#include <utility>

namespace meshmark {

namespace {

// One table per enum, in declaration order: to_string indexes it, parse searches it.
constexpr std::array kJobKinds{"prepare", "embed", "detect"};
constexpr std::array kJobStates{"queued", "running", "succeeded", "failed", "canceled"};
constexpr std::array kModelStates{"preparing", "ready", "failed"};
constexpr std::array kEmbeddingStates{"pending", "ready"};

template <typename Enum, std::size_t N>
std::optional<Enum> find_word(const std::array<const char*, N>& words, std::string_view text) {
  for (std::size_t i = 0; i < N; ++i)
    if (text == words[i]) return static_cast<Enum>(i);
  return std::nullopt;
}

}  // namespace

std::string to_string(JobKind kind) { return kJobKinds[static_cast<std::size_t>(kind)]; }
std::string to_string(JobState state) { return kJobStates[static_cast<std::size_t>(state)]; }
std::string to_string(ModelState state) { return kModelStates[static_cast<std::size_t>(state)]; }
std::string to_string(EmbeddingState state) { return kEmbeddingStates[static_cast<std::size_t>(state)]; }

std::optional<JobKind> parse_job_kind(std::string_view text) { return find_word<JobKind>(kJobKinds, text); }
std::optional<JobState> parse_job_state(std::string_view text) { return find_word<JobState>(kJobStates, text); }
std::optional<ModelState> parse_model_state(std::string_view text) { return find_word<ModelState>(kModelStates, text); }
std::optional<EmbeddingState> parse_embedding_state(std::string_view text) {
  return find_word<EmbeddingState>(kEmbeddingStates, text);
}

bool is_final(JobState state) {
  return state == JobState::succeeded || state == JobState::failed || state == JobState::canceled;
}

}  // namespace meshmark
