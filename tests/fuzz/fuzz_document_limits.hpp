#pragma once
// The limits the document targets read under: small enough that an input which amplifies shows
// up as a refusal or a finding, large enough for every seed.

#include "core/io/mesh_document.hpp"

inline meshmark::DocumentReadOptions fuzz_document_options() {
  meshmark::DocumentReadOptions options;
  options.limits.max_vertices = 100000;
  options.limits.max_faces = 200000;
  options.limits.max_file_bytes = 1 << 22;
  return options;
}
