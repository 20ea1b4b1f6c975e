#include "core/util/json_nesting_depth.hpp"

#include <algorithm>

namespace meshmark {

JsonShape json_shape(std::string_view text) {
  // Every value but the first of an array or object follows a comma, and the first of each
  // container (or the document) is one more: commas + 2 × containers + 1 bounds them.
  std::size_t depth = 0, deepest = 0, commas = 0, containers = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == ',') ++commas;
    else if (c == '[' || c == '{') deepest = std::max(deepest, ++depth), ++containers;
    else if ((c == ']' || c == '}') && depth > 0) --depth;
  }
  return {deepest, commas + 2 * containers + 1};
}

}  // namespace meshmark
