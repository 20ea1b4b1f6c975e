#include "proto/job_specs.hpp"

#include <gtest/gtest.h>

namespace meshmark {
namespace {

EmbedJobSpec an_embed_spec() {
  return {parse_embed_request({{"recipient", "shop"}, {"strength", 0.2}}), "emb_1", "glb", "a1b2"};
}

TEST(JobSpecs, EachKindIsReadBackAsWritten) {
  const std::vector<JobSpec> specs = {PrepareJobSpec{}, an_embed_spec(),
                                      DetectJobSpec{parse_detect_query("paper", "", "32"), 1234}};
  for (const JobSpec& spec : specs) {
    const nlohmann::json j = job_spec_json(spec);
    EXPECT_EQ(j.at("version"), kJobSpecVersion);
    const JobSpec again = parse_job_spec(job_kind(spec), j);
    EXPECT_EQ(job_kind(again), job_kind(spec));
    EXPECT_EQ(job_spec_json(again), j);
  }
  const auto detect = std::get<DetectJobSpec>(parse_job_spec(JobKind::detect, job_spec_json(specs[2])));
  EXPECT_EQ(detect.request.bits, 32);
  EXPECT_TRUE(detect.request.settings_given);
  EXPECT_EQ(detect.suspect_vertices, 1234);
}

TEST(JobSpecs, ADetectionKeepsItsSuspectsDigestAndOlderSpecsReadWithout) {
  const DetectJobSpec spec(parse_detect_query("", "", ""), 10, "9f86d081");
  nlohmann::json j = job_spec_json(spec);
  EXPECT_EQ(std::get<DetectJobSpec>(parse_job_spec(JobKind::detect, j)).suspect_sha256, "9f86d081");
  j.erase("suspect_sha256");
  EXPECT_EQ(std::get<DetectJobSpec>(parse_job_spec(JobKind::detect, j)).suspect_sha256, "");
}

TEST(JobSpecs, AnotherVersionOrAShapeOfAnotherKindIsRefused) {
  nlohmann::json j = job_spec_json(an_embed_spec());
  j["version"] = kJobSpecVersion + 1;
  EXPECT_THROW(parse_job_spec(JobKind::embed, j), std::invalid_argument);
  EXPECT_THROW(parse_job_spec(JobKind::embed, job_spec_json(PrepareJobSpec{})), std::invalid_argument);
  EXPECT_THROW(parse_job_spec(JobKind::detect, job_spec_json(PrepareJobSpec{})), std::invalid_argument);
  EXPECT_THROW(parse_job_spec(JobKind::prepare, nlohmann::json::object()), std::invalid_argument) << "no version";
}

// The two shapes jobs had before specs were versioned: the client's request flat beside the
// daemon's keys, then nested under "request".
TEST(JobSpecs, EarlierStoredShapesAreUpgraded) {
  const nlohmann::json flat = {{"recipient", "shop"},
                               {"scheme", "spread"},
                               {"embedding_id", "emb_1"},
                               {"output_format", "ply"},
                               {"assigned_payload", "ab"}};
  const nlohmann::json nested = {{"request", {{"recipient", "shop"}, {"scheme", "spread"}}},
                                 {"embedding_id", "emb_1"},
                                 {"output_format", "ply"},
                                 {"assigned_payload", "ab"}};
  for (const nlohmann::json& stored : {flat, nested}) {
    const auto spec = std::get<EmbedJobSpec>(parse_job_spec(JobKind::embed, upgrade_job_spec(JobKind::embed, stored)));
    EXPECT_EQ(spec.request.recipient, "shop");
    EXPECT_EQ(spec.embedding_id, "emb_1");
    EXPECT_EQ(spec.output_format, "ply");
    EXPECT_EQ(spec.assigned_payload, "ab");
  }
  const nlohmann::json detect = {{"scheme", "spread"}, {"wavelet", "linear-lifting"}, {"bits", 16}};
  const auto d = std::get<DetectJobSpec>(parse_job_spec(JobKind::detect, upgrade_job_spec(JobKind::detect, detect)));
  EXPECT_EQ(d.request.bits, 16);
  EXPECT_TRUE(d.request.settings_given) << "the default of jobs stored before the flag";
  EXPECT_NO_THROW(parse_job_spec(JobKind::prepare, upgrade_job_spec(JobKind::prepare, nlohmann::json::object())));
}

}  // namespace
}  // namespace meshmark
