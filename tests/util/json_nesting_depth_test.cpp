#include "core/util/json_nesting_depth.hpp"

#include <gtest/gtest.h>

#include <string>

namespace meshmark {
namespace {

TEST(JsonNestingDepth, SkipsBracketsInsideStrings) {
  EXPECT_EQ(json_nesting_depth(R"({"a": [1, [2, {"b": 3}]]})"), 4u);
  EXPECT_EQ(json_nesting_depth(R"({"a": "[[[[\"[[["})"), 1u);
  EXPECT_EQ(json_nesting_depth(std::string(100000, '[')), 100000u);
  EXPECT_EQ(json_nesting_depth("12"), 0u);
}

}  // namespace
}  // namespace meshmark
