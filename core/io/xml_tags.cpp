#include "core/io/xml_tags.hpp"

#include <algorithm>

#include "core/io/mesh_io_error.hpp"

namespace meshmark {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool is_name_char(char c) {
  return !is_space(c) && c != '=' && c != '>' && c != '/' && c != '<' && c != '"' && c != '\'';
}

}  // namespace

bool XmlTagReader::next(XmlTag& tag, const std::string& source) {
  const auto fail = [&](const std::string& what) -> void {
    throw MeshIoError(source + ": line " + std::to_string(line_) + ": " + what);
  };
  const auto advance_to = [&](std::size_t to) {
    line_ += static_cast<std::size_t>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(at_),
                                                 text_.begin() + static_cast<std::ptrdiff_t>(to), '\n'));
    at_ = to;
  };
  const auto skip_past = [&](std::string_view terminator, const char* what) {
    const std::size_t end = text_.find(terminator, at_);
    if (end == std::string_view::npos) fail(std::string("an unterminated ") + what);
    advance_to(end + terminator.size());
  };
  for (;;) {
    const std::size_t open = text_.find('<', at_);
    if (open == std::string_view::npos) {
      advance_to(text_.size());
      return false;
    }
    advance_to(open);
    const std::string_view rest = text_.substr(at_);
    if (rest.substr(0, 4) == "<!--") {
      skip_past("-->", "comment");
    } else if (rest.substr(0, 9) == "<![CDATA[") {
      skip_past("]]>", "CDATA section");
    } else if (rest.substr(0, 2) == "<?") {
      skip_past("?>", "processing instruction");
    } else if (rest.substr(0, 2) == "<!") {
      fail("DOCTYPE and other declarations are not read");
    } else {
      break;
    }
  }
  // <name attr="value" ...> or </name> or <name .../>
  tag.attributes.clear();
  tag.line = line_;
  std::size_t i = at_ + 1;
  tag.closing = i < text_.size() && text_[i] == '/';
  if (tag.closing) ++i;
  const std::size_t name_start = i;
  while (i < text_.size() && is_name_char(text_[i])) ++i;
  if (i == name_start) fail("a '<' that opens no tag");
  tag.name = text_.substr(name_start, i - name_start);
  tag.empty = false;
  for (;;) {
    while (i < text_.size() && is_space(text_[i])) ++i;
    if (i >= text_.size()) fail("the tag <" + std::string(tag.name.substr(0, 40)) + "> is not closed");
    if (text_[i] == '>') {
      ++i;
      break;
    }
    if (text_[i] == '/' && i + 1 < text_.size() && text_[i + 1] == '>') {
      tag.empty = true;
      i += 2;
      break;
    }
    if (tag.closing) fail("a closing tag with attributes");
    const std::size_t attribute_start = i;
    while (i < text_.size() && is_name_char(text_[i])) ++i;
    if (i == attribute_start) fail("a stray character in the tag <" + std::string(tag.name.substr(0, 40)) + ">");
    XmlAttribute a;
    a.name = text_.substr(attribute_start, i - attribute_start);
    while (i < text_.size() && is_space(text_[i])) ++i;
    if (i >= text_.size() || text_[i] != '=')
      fail("the attribute '" + std::string(a.name.substr(0, 40)) + "' has no value");
    ++i;
    while (i < text_.size() && is_space(text_[i])) ++i;
    if (i >= text_.size() || (text_[i] != '"' && text_[i] != '\'')) fail("an attribute value without quotes");
    const char quote = text_[i++];
    const std::size_t close = text_.find(quote, i);
    if (close == std::string_view::npos) fail("an attribute value is not closed");
    a.value = text_.substr(i, close - i);
    if (a.value.find('<') != std::string_view::npos) fail("a '<' inside an attribute value");
    a.span = {i, close};
    tag.attributes.push_back(a);
    i = close + 1;
  }
  advance_to(i);
  return true;
}

}  // namespace meshmark
