#include "proto/api.hpp"

#include <gtest/gtest.h>

namespace meshmark {
namespace {

TEST(ParseEmbedRequest, APayloadAloneUsesTheDefaults) {
  const EmbedRequest r = parse_embed_request({{"payload", "0123456789ABCDEF"}});
  ASSERT_TRUE(r.payload);
  EXPECT_EQ(*r.payload, "0123456789abcdef");
  EXPECT_EQ(r.options.scheme, WatermarkOptions{}.scheme);
  EXPECT_TRUE(r.recipient.empty());
}

TEST(ParseEmbedRequest, ARecipientAloneAsksForAnAssignedPayload) {
  const EmbedRequest r = parse_embed_request({{"recipient", "shop"}});
  EXPECT_FALSE(r.payload);
  EXPECT_EQ(r.recipient, "shop");
}

TEST(ParseEmbedRequest, WhoAskedIsALabelKeptThroughTheJobSpec) {
  const EmbedRequest r = parse_embed_request({{"recipient", "shop"}, {"requested_by", "Ana (licensing)"}});
  EXPECT_EQ(r.requested_by, "Ana (licensing)");
  EXPECT_EQ(parse_embed_request(embed_request_json(r)).requested_by, "Ana (licensing)");
  EXPECT_FALSE(embed_request_json(parse_embed_request({{"recipient", "shop"}})).contains("requested_by"));
  for (const nlohmann::json& asked : {nlohmann::json(5), nlohmann::json("a\nb"), nlohmann::json(std::string(201, 'a'))})
    EXPECT_THROW(parse_embed_request({{"recipient", "shop"}, {"requested_by", asked}}), std::invalid_argument) << asked;
  const auto batch = parse_embed_requests({{"recipients", {"a", "b"}}, {"requested_by", "Ana"}});
  ASSERT_EQ(batch.size(), 2u);
  EXPECT_EQ(batch[1].requested_by, "Ana");
}

TEST(ParseEmbedRequest, RefusesWhatItCannotUse) {
  for (const char* body : {R"([])", R"({})", R"({"payload": "zz"})", R"({"payload": 5})", R"({"recipient": 5})",
                           R"({"payload": "ab", "strength": 0})", R"({"payload": "ab", "strength": "big"})",
                           R"({"payload": "ab", "strength": 1e-300})", R"({"payload": "ab", "strength": 5.01})",
                           R"({"payload": "ab", "wavelet": "haar"})", R"({"payload": "ab", "format": "fbx"})"})
    EXPECT_THROW(parse_embed_request(nlohmann::json::parse(body)), std::invalid_argument) << body;
  EXPECT_THROW(parse_embed_request({{"payload", std::string(kMaxPayloadBits / 4 + 1, 'a')}}), std::invalid_argument);
  EXPECT_THROW(parse_embed_request(nlohmann::json::parse("nonsense", nullptr, false)), std::invalid_argument);
}

TEST(ParseDetectQuery, ChecksTheBitCount) {
  EXPECT_EQ(parse_detect_query("", "", "").bits, 64);
  EXPECT_EQ(parse_detect_query("paper", "linear", "32").bits, 32);
  for (const char* bits : {"0", "7", "-8", "12x", "100000"})
    EXPECT_THROW(parse_detect_query("", "", bits), std::invalid_argument) << bits;
}

}  // namespace
}  // namespace meshmark
