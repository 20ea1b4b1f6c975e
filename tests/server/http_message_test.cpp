#include "server/http/http_message.hpp"

#include <gtest/gtest.h>

namespace meshmark::server {
namespace {

TEST(HttpMessage, PercentEscapesDecodeToAnyBytes) {
  EXPECT_EQ(percent_decode("a%20b%FF", false), std::string("a b\xFF"));
  EXPECT_EQ(percent_decode("a+b", true), std::string("a b"));
  EXPECT_EQ(percent_decode("a+b", false), std::string("a+b"));
}

TEST(HttpMessage, MalformedEscapesAreRefused) {
  for (const char* bad : {"%", "%F", "%G0", "ab%"}) EXPECT_FALSE(percent_decode(bad, false)) << bad;
}

TEST(HttpMessage, TargetsSplitIntoDecodedPathAndQuery) {
  std::string path;
  std::multimap<std::string, std::string> query;
  ASSERT_TRUE(split_target("/v1/models?format=obj&name=my+bunny%21&flag", path, query));
  EXPECT_EQ(path, "/v1/models");
  EXPECT_EQ(query.find("format")->second, "obj");
  EXPECT_EQ(query.find("name")->second, "my bunny!");
  EXPECT_EQ(query.find("flag")->second, "");
  EXPECT_FALSE(split_target("/a%zz", path, query));
}

TEST(HttpMessage, HeaderNamesMatchWithoutCase) {
  const HeaderList headers = {{"content-length", "3"}, {"X-A", "1"}, {"x-a", "2"}};
  EXPECT_EQ(header_value(headers, "Content-Length"), "3");
  EXPECT_EQ(header_count(headers, "X-a"), 2u);
  EXPECT_EQ(header_value(headers, "Missing"), "");
}

}  // namespace
}  // namespace meshmark::server
