#pragma once
// The reader tests' probe: what reading a text says when it refuses it.

#include <string>

#include "core/io/mesh_io_error.hpp"
#include "core/io/read_mesh.hpp"

namespace meshmark::test {

/// The message of the MeshIoError that reading `text` as `format` throws ("" if none).
inline std::string read_error(const std::string& text, MeshFormat format, const ReadOptions& options = {}) {
  try {
    read_mesh_from_memory(text, format, options, "input");
  } catch (const MeshIoError& e) {
    return e.what();
  }
  return "";
}

}  // namespace meshmark::test
