#pragma once
// How deep JSON text nests, found without parsing it: lets a caller refuse a hostile document
// before a recursive consumer sees it (the daemon's requests, glTF files).

#include <cstddef>
#include <string_view>

namespace meshmark {

/// The deepest nesting of arrays and objects in JSON text (strings skipped).
std::size_t json_nesting_depth(std::string_view text);

}  // namespace meshmark
