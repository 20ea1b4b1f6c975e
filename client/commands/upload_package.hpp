#pragma once
// A mesh file as the daemon takes it in one request: alone, or — a glTF or an OBJ that refers
// to other files (buffers, material libraries, textures) — zipped with them, as NAME.gltf.zip
// travels; a .zip the user made goes as it is.

#include <filesystem>
#include <string>
#include <vector>

#include "core/io/mesh_format.hpp"

namespace meshmark::cli {

struct UploadPackage {
  std::string bytes;
  MeshFormat format = MeshFormat::ply;
  std::vector<std::string> packed;   ///< companion files zipped with the main one
  std::vector<std::string> missing;  ///< companions it refers to that are not beside it
};

/// Throws (MeshIoError, std::runtime_error) saying what is wrong: an unreadable file, a ZIP that
/// holds no mesh file or several.
UploadPackage package_for_upload(const std::filesystem::path& file);

/// "warning: cow.obj refers to cow.mtl, which is not beside it: …" for each missing companion.
void warn_missing_companions(const std::filesystem::path& file, const UploadPackage& package);

}  // namespace meshmark::cli
