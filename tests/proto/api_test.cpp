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
