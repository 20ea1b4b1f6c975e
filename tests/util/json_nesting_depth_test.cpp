#include "core/util/json_nesting_depth.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

namespace meshmark {
namespace {

TEST(JsonNestingDepth, SkipsBracketsInsideStrings) {
  EXPECT_EQ(json_nesting_depth(R"({"a": [1, [2, {"b": 3}]]})"), 4u);
  EXPECT_EQ(json_nesting_depth(R"({"a": "[[[[\"[[["})"), 1u);
  EXPECT_EQ(json_nesting_depth(std::string(100000, '[')), 100000u);
  EXPECT_EQ(json_nesting_depth("12"), 0u);
}

// Every value a parse creates, containers included (keys are not values).
std::size_t values_in(const nlohmann::json& j) {
  std::size_t n = 1;
  if (j.is_structured())
    for (const auto& child : j) n += values_in(child);
  return n;
}

// The bound holds for any text a parser accepts, and is close: a caller can refuse a document
// whose tree would be too large before parsing it.
TEST(JsonShape, BoundsTheValuesAParseCreates) {
  for (const char* text : {"12", "[]", "{}", R"({"a": [1, [2, {"b": 3}]], "c": "x,[{"})", "[[],[],[[1,2],[3]]]",
                           R"({"k": {"k": {"k": {}}}, "l": [true, false, null, 1e5, "s"]})"}) {
    const std::size_t actual = values_in(nlohmann::json::parse(text)), bound = json_shape(text).values;
    EXPECT_GE(bound, actual) << text;
    EXPECT_LE(bound, 3 * actual) << text;
  }
}

}  // namespace
}  // namespace meshmark
