#pragma once
// Writing a marked document to disk for `meshmark embed`: the main file where the user asked,
// changed companions (a glTF's .bin) beside it under the output's name, unchanged companions
// (textures, .mtl) copied when the output goes to another folder. The original and its
// companions are never overwritten.

#include <filesystem>
#include <string>
#include <vector>

#include "core/io/mesh_document.hpp"

namespace meshmark::cli {

/// The names changed companions take: "<out stem>.bin" for the input's own "<in stem>.bin",
/// "<out stem>_<name>" for others.
CompanionNames companion_names(const std::filesystem::path& in, const std::filesystem::path& out);

/// Refuses, before any work, an output that would overwrite the input or one of its companion
/// files, or a format the input cannot be written in (a glb, gltf or 3mf from another format).
void check_output(const std::filesystem::path& in, const std::filesystem::path& out, const MeshDocument& document);

/// Writes `files` (from document.write with companion_names) for the document read from `in`,
/// with the unchanged companions it refers to when `out` is in another folder;
/// returns the paths written. Every destination is checked before anything is written: throws
/// std::runtime_error when one would overwrite the input or an existing different file.
std::vector<std::filesystem::path> write_document_files(const std::filesystem::path& in,
                                                        const std::filesystem::path& out, const MeshDocument& document,
                                                        const DocumentFiles& files);

}  // namespace meshmark::cli
