// The lifecycle words: each enum value has one word, and only those words parse.

#include "proto/states.hpp"

#include <gtest/gtest.h>

namespace meshmark {
namespace {

TEST(States, EveryJobStateRoundTripsThroughItsWord) {
  for (JobState s : {JobState::queued, JobState::running, JobState::succeeded, JobState::failed, JobState::canceled})
    EXPECT_EQ(parse_job_state(to_string(s)), s) << to_string(s);
  for (JobKind k : {JobKind::prepare, JobKind::embed, JobKind::detect}) EXPECT_EQ(parse_job_kind(to_string(k)), k);
  for (ModelState s : {ModelState::preparing, ModelState::ready, ModelState::failed})
    EXPECT_EQ(parse_model_state(to_string(s)), s);
  for (EmbeddingState s : {EmbeddingState::pending, EmbeddingState::ready})
    EXPECT_EQ(parse_embedding_state(to_string(s)), s);
}

TEST(States, TheWordsAreTheApis) {
  EXPECT_EQ(to_string(JobState::canceled), "canceled");
  EXPECT_EQ(to_string(ModelState::preparing), "preparing");
  EXPECT_EQ(to_string(JobKind::detect), "detect");
}

TEST(States, OtherWordsDoNotParse) {
  EXPECT_FALSE(parse_job_state("cancelled"));
  EXPECT_FALSE(parse_job_state("Queued"));
  EXPECT_FALSE(parse_job_kind(""));
  EXPECT_FALSE(parse_model_state("done"));
}

TEST(States, OnlySucceededFailedAndCanceledAreFinal) {
  EXPECT_FALSE(is_final(JobState::queued));
  EXPECT_FALSE(is_final(JobState::running));
  EXPECT_TRUE(is_final(JobState::succeeded));
  EXPECT_TRUE(is_final(JobState::failed));
  EXPECT_TRUE(is_final(JobState::canceled));
}

}  // namespace
}  // namespace meshmark
