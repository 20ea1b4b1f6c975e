// XmlTagReader alone on arbitrary text: it reads tags until the end or refuses with MeshIoError;
// every tag it reports is ahead of the last, and every attribute's value is the text its span
// names; nothing else escapes.

#include "core/io/mesh_io_error.hpp"
#include "core/io/xml_tags.hpp"
#include "tests/fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = as_text(data, size);
  meshmark::XmlTagReader reader(text);
  meshmark::XmlTag tag;
  std::size_t tags = 0, last_line = 1;
  try {
    while (reader.next(tag, "fuzz")) {
      if (++tags > size) __builtin_trap();  // every tag takes at least one byte
      if (tag.line < last_line || tag.name.empty()) __builtin_trap();
      last_line = tag.line;
      for (const meshmark::XmlAttribute& a : tag.attributes) {
        if (a.span.end > size || a.span.begin > a.span.end) __builtin_trap();
        if (text.substr(a.span.begin, a.span.end - a.span.begin) != a.value) __builtin_trap();
      }
    }
  } catch (const meshmark::MeshIoError&) {
  }
  return 0;
}
