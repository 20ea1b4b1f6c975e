#pragma once
// Where each value of a JSON text is, by JSON pointer ("/accessors/3/min"): so that a document can
// replace a value (or add a member to an object) and leave every other byte of the text as it
// was. nlohmann::json parses the meaning; this only finds places.

#include <map>
#include <string>
#include <string_view>

#include "core/io/byte_edits.hpp"

namespace meshmark {

class JsonSpans {
 public:
  /// Scans `text` (a valid JSON document, at most `max_depth` deep). Throws MeshIoError when it
  /// is not JSON.
  explicit JsonSpans(std::string_view text, int max_depth = 64);

  /// The span of the value at `pointer` (without surrounding blanks); nullopt-like: {0, 0} when
  /// absent.
  bool has(const std::string& pointer) const { return spans_.count(pointer) > 0; }
  ByteSpan value(const std::string& pointer) const;
  /// The position just after the opening brace of the object at `pointer`: where a new member
  /// `"key": value,` can be inserted.
  std::size_t object_start(const std::string& pointer) const;

 private:
  void scan_value(const std::string& pointer, int depth);
  void skip_blanks();
  void scan_string();
  [[noreturn]] void fail(const std::string& what) const;

  std::string_view text_;
  std::size_t pos_ = 0;
  int max_depth_;
  std::map<std::string, ByteSpan> spans_;
};

}  // namespace meshmark
