#pragma once
// A written copy as its reader sees it: the welded scene read back from the bytes about to be
// handed out, in the format's own precision (float32, quantized or Draco glTF, text digits).

#include <functional>
#include <string>

#include "core/io/mesh_document.hpp"

namespace meshmark {

/// The scene of a document written in memory: `files` as MeshDocument::write gives them (the
/// main file ""), companions not among them read through `unchanged` (by relative URI).
Mesh read_back(const DocumentFiles& files, MeshFormat format,
               const std::function<std::string(const std::string& uri)>& unchanged, const ReadOptions& limits = {});

/// The scene of a copy in one container (a file, or a ZIP with its companions).
Mesh read_back(const std::string& bytes, MeshFormat format, const ReadOptions& limits = {});

}  // namespace meshmark
