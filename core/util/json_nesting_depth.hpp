#pragma once
// How deep JSON text nests and how many values it can hold, found without parsing it: lets a
// caller refuse a hostile document before a recursive consumer sees it, or before a parser
// builds a tree that costs ~100 bytes per value (the daemon's requests, glTF files).

#include <cstddef>
#include <string_view>

namespace meshmark {

struct JsonShape {
  std::size_t depth = 0;   ///< the deepest nesting of arrays and objects
  std::size_t values = 0;  ///< an upper bound on the values a parse creates (keys not counted)
};

/// The shape of JSON text (strings skipped), in one pass.
JsonShape json_shape(std::string_view text);

/// The deepest nesting of arrays and objects in JSON text (strings skipped).
inline std::size_t json_nesting_depth(std::string_view text) { return json_shape(text).depth; }

}  // namespace meshmark
