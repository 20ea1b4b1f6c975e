#pragma once
// A forward-only reader over text in memory that knows its line number. Used by the ASCII
// parsers; locale-independent (std::from_chars), never reads past the end.

#include <charconv>
#include <cstddef>
#include <string_view>

namespace meshmark {

class TextCursor {
 public:
  explicit TextCursor(std::string_view text) : text_(text) {}

  bool at_end() const { return pos_ >= text_.size(); }
  std::size_t line() const { return line_; }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return text_.size() - pos_; }

  /// Moves forward to byte `position`, counting the lines passed.
  void skip_to(std::size_t position) {
    while (pos_ < position && pos_ < text_.size()) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  /// Skips spaces and tabs (not line breaks).
  void skip_blanks() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }

  /// True at a line break, at the end, or at `comment` (if non-zero); skips blanks first.
  bool at_line_end(char comment = 0) {
    skip_blanks();
    if (pos_ >= text_.size()) return true;
    const char c = text_[pos_];
    return c == '\n' || c == '\r' || (comment != 0 && c == comment);
  }

  /// Moves to the first character after the next line break.
  void next_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    if (pos_ < text_.size()) {
      ++pos_;
      ++line_;
    }
  }

  /// Skips blanks and line breaks; lines starting with `comment` count as blank.
  void skip_whitespace_and_comments(char comment) {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ' ' || c == '\t' || c == '\r') {
        ++pos_;
      } else if (c == '\n') {
        ++pos_;
        ++line_;
      } else if (c == comment) {
        next_line();
      } else {
        break;
      }
    }
  }

  /// The next run of non-blank characters on this line (empty at a line end).
  std::string_view token() {
    skip_blanks();
    const std::size_t start = pos_;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') break;
      ++pos_;
    }
    return text_.substr(start, pos_ - start);
  }

  /// Parses a whole token as a number; false if the token is empty or not entirely a number.
  template <typename Number>
  bool read_number(Number& value) {
    std::string_view t = token();
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    if (t.empty()) return false;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    return ec == std::errc() && end == t.data() + t.size();
  }

  /// The rest of the current line, without the line break.
  std::string_view rest_of_line() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n' && text_[pos_] != '\r') ++pos_;
    return text_.substr(start, pos_ - start);
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

/// Parses a prefix of `text` as an integer (for "12/5/3" style tokens); false if none.
inline bool parse_leading_integer(std::string_view text, long long& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end != text.data() && (end == text.data() + text.size() || *end == '/');
}

}  // namespace meshmark
