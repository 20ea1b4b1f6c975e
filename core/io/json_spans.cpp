#include "core/io/json_spans.hpp"

#include "core/io/mesh_io_error.hpp"

namespace meshmark {

JsonSpans::JsonSpans(std::string_view text, int max_depth) : text_(text), max_depth_(max_depth) {
  skip_blanks();
  scan_value("", 0);
  skip_blanks();
  if (pos_ != text_.size()) fail("text after the JSON value");
}

ByteSpan JsonSpans::value(const std::string& pointer) const {
  const auto it = spans_.find(pointer);
  if (it == spans_.end()) throw MeshIoError("glTF JSON: no value at " + pointer);
  return it->second;
}

std::size_t JsonSpans::object_start(const std::string& pointer) const {
  const ByteSpan span = value(pointer);
  if (text_[span.begin] != '{') throw MeshIoError("glTF JSON: " + pointer + " is not an object");
  return span.begin + 1;
}

void JsonSpans::fail(const std::string& what) const {
  throw MeshIoError("glTF JSON, byte " + std::to_string(pos_) + ": " + what);
}

void JsonSpans::skip_blanks() {
  while (pos_ < text_.size() &&
         (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\n' || text_[pos_] == '\r'))
    ++pos_;
}

void JsonSpans::scan_string() {
  if (pos_ >= text_.size() || text_[pos_] != '"') fail("a string was expected");
  for (++pos_; pos_ < text_.size(); ++pos_) {
    if (text_[pos_] == '\\') ++pos_;
    else if (text_[pos_] == '"') {
      ++pos_;
      return;
    }
  }
  fail("a string does not end");
}

// Pointer tokens escape '~' and '/' (RFC 6901).
static std::string pointer_token(std::string_view raw) {
  std::string out;
  for (const char c : raw) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

void JsonSpans::scan_value(const std::string& pointer, int depth) {
  if (depth > max_depth_) fail("the JSON nests deeper than " + std::to_string(max_depth_) + " levels");
  if (pos_ >= text_.size()) fail("a value was expected");
  const std::size_t begin = pos_;
  const char c = text_[pos_];
  if (c == '{') {
    ++pos_;
    skip_blanks();
    if (pos_ < text_.size() && text_[pos_] == '}') {
      ++pos_;
    } else {
      while (true) {
        skip_blanks();
        const std::size_t key_begin = pos_;
        scan_string();
        const std::string_view key =
            text_.substr(key_begin + 1, pos_ - key_begin - 2);  // escapes kept: glTF keys have none
        skip_blanks();
        if (pos_ >= text_.size() || text_[pos_] != ':') fail("':' was expected");
        ++pos_;
        skip_blanks();
        scan_value(pointer + "/" + pointer_token(key), depth + 1);
        skip_blanks();
        if (pos_ < text_.size() && text_[pos_] == ',') {
          ++pos_;
          continue;
        }
        if (pos_ < text_.size() && text_[pos_] == '}') {
          ++pos_;
          break;
        }
        fail("',' or '}' was expected");
      }
    }
  } else if (c == '[') {
    ++pos_;
    skip_blanks();
    if (pos_ < text_.size() && text_[pos_] == ']') {
      ++pos_;
    } else {
      for (std::size_t index = 0;; ++index) {
        skip_blanks();
        scan_value(pointer + "/" + std::to_string(index), depth + 1);
        skip_blanks();
        if (pos_ < text_.size() && text_[pos_] == ',') {
          ++pos_;
          continue;
        }
        if (pos_ < text_.size() && text_[pos_] == ']') {
          ++pos_;
          break;
        }
        fail("',' or ']' was expected");
      }
    }
  } else if (c == '"') {
    scan_string();
  } else {
    // A number, true, false or null: up to the next delimiter (nlohmann checked the grammar).
    while (pos_ < text_.size() && text_[pos_] != ',' && text_[pos_] != '}' && text_[pos_] != ']' &&
           text_[pos_] != ' ' && text_[pos_] != '\n' && text_[pos_] != '\r' && text_[pos_] != '\t')
      ++pos_;
    if (pos_ == begin) fail("a value was expected");
  }
  spans_[pointer] = {begin, pos_};
}

}  // namespace meshmark
