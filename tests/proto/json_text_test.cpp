#include "proto/json_text.hpp"

#include <gtest/gtest.h>

namespace meshmark {
namespace {

TEST(JsonText, InvalidUtf8IsReplacedNotThrownOn) {
  const nlohmann::json j = {{"path", std::string("/\xFF\xFE")}};
  EXPECT_THROW(j.dump(), nlohmann::json::type_error);
  const std::string text = json_text(j);
  EXPECT_EQ(nlohmann::json::parse(text)["path"].get<std::string>(), "/\xEF\xBF\xBD\xEF\xBF\xBD");
}

TEST(JsonText, PrintableUtf8RefusesControlsAndBrokenSequences) {
  EXPECT_TRUE(is_printable_utf8("Studio Ä 北京 🎨"));
  EXPECT_FALSE(is_printable_utf8("a\nb"));
  EXPECT_FALSE(is_printable_utf8(std::string("a\0b", 3)));
  EXPECT_FALSE(is_printable_utf8("\xFF"));
  EXPECT_FALSE(is_printable_utf8("\xC0\xAF"));      // overlong '/'
  EXPECT_FALSE(is_printable_utf8("\xED\xA0\x80"));  // a surrogate
  EXPECT_FALSE(is_printable_utf8("\xE2\x82"));      // cut short
  EXPECT_FALSE(
      is_printable_utf8("invoice\xE2\x80\xAE"
                        "fdp.exe"));  // U+202E right-to-left override
  EXPECT_FALSE(
      is_printable_utf8("a\xE2\x81\xA6"
                        "b"));  // U+2066 left-to-right isolate
  EXPECT_FALSE(
      is_printable_utf8("a\xC2\x85"
                        "b"));                                         // U+0085, a C1 control
  EXPECT_TRUE(is_printable_utf8("\xD8\xB3\xD9\x84\xD8\xA7\xD9\x85"));  // Arabic text itself is fine
}

TEST(JsonText, ClippingKeepsWholeCharacters) {
  EXPECT_EQ(clip_for_message("short", 10), "short");
  EXPECT_EQ(clip_for_message("\xC3\xA4\xC3\xA4\xC3\xA4", 3), "\xC3\xA4\xE2\x80\xA6");
}

}  // namespace
}  // namespace meshmark
