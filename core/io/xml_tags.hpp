#pragma once
// The tags of an XML document one after another, with their attributes and where each attribute
// value lies in the text: enough to read a 3MF model and to rewrite single values in place.
// Comments, processing instructions and CDATA are skipped; a DOCTYPE is refused (its entities
// could expand without bound); text content is not reported.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/byte_edits.hpp"

namespace meshmark {

struct XmlAttribute {
  std::string_view name;   ///< qualified, as written ("x", "p:path")
  std::string_view value;  ///< raw, entities not decoded
  ByteSpan span;           ///< of the value, between its quotes
};

struct XmlTag {
  std::string_view name;  ///< qualified
  bool closing = false;   ///< </name>
  bool empty = false;     ///< <name ... />
  std::vector<XmlAttribute> attributes;
  std::size_t line = 1;

  /// The attribute of that qualified name; null if absent.
  const XmlAttribute* find(std::string_view attribute) const {
    for (const XmlAttribute& a : attributes)
      if (a.name == attribute) return &a;
    return nullptr;
  }
  /// The part of the name after its prefix.
  std::string_view local_name() const {
    const auto colon = name.find(':');
    return colon == std::string_view::npos ? name : name.substr(colon + 1);
  }
  std::string_view prefix() const {
    const auto colon = name.find(':');
    return colon == std::string_view::npos ? std::string_view() : name.substr(0, colon);
  }
};

class XmlTagReader {
 public:
  explicit XmlTagReader(std::string_view text) : text_(text) {}

  /// The next tag into `tag` (its attribute list reused); false at the end of the text.
  /// Throws MeshIoError (prefixed with `source`) on malformed markup.
  bool next(XmlTag& tag, const std::string& source);

 private:
  std::string_view text_;
  std::size_t at_ = 0;
  std::size_t line_ = 1;
};

}  // namespace meshmark
