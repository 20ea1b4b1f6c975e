#pragma once
// A document as bytes in memory, alone or in a ZIP with its companion files (how a .gltf with
// external buffers and textures, or an .obj with its .mtl, travels in one upload), written back
// in the same container: a ZIP comes back as the same ZIP with only changed files replaced.

#include <memory>
#include <optional>
#include <string>

#include "core/io/mesh_document.hpp"
#include "core/io/zip_archive.hpp"

namespace meshmark {

/// True when `bytes` start like a ZIP archive.
bool looks_zipped(std::string_view bytes);

class PackagedDocument {
 public:
  /// Reads `bytes` as `format`; a ZIP (any format but 3MF, which is one) must hold exactly one
  /// file with that format's extension, whose companions are read from beside it in the archive.
  /// Throws MeshIoError (MeshLimitError for limits), naming `source`.
  PackagedDocument(std::string bytes, MeshFormat format, const DocumentReadOptions& options, const std::string& source);

  const MeshDocument& document() const { return *document_; }
  bool zipped() const { return zip_.has_value(); }
  /// The main file's name inside the ZIP ("" when not zipped).
  const std::string& main_entry() const { return main_; }

  /// The container after moving the slots (see MeshDocument::write).
  std::string write(const Vertices& positions, const NormalRotations& rotations) const;

 private:
  std::optional<ZipArchive> zip_;
  std::string main_, folder_;
  std::string source_;
  std::unique_ptr<MeshDocument> document_;
};

}  // namespace meshmark
