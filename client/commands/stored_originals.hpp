#pragma once
// The originals `embed` keeps in the records folder, each as it was prepared
// (copy_record_files.hpp). An original's preparation — its sphere map above all — follows the
// file's exact numbers, not only its shape, so a copy reads only against those numbers; a master
// re-exported since (fewer digits, vertices renumbered, moved) is recognised here as the stored
// original it is, and `detect --original` reads against that one.

#include <filesystem>
#include <vector>

#include "core/grid/sphere_grid.hpp"
#include "core/watermark/prepared_model.hpp"

namespace meshmark::cli {

/// "meshmark-original-<first 16 hex digits of the digest>-<base>": what `embed` names the original
/// it stores (".ply") and its preparation (".prepared"), shared by every copy of it in the folder.
std::string stored_original_stem(const std::string& digest, BaseSolid base);

struct StoredOriginal {
  std::filesystem::path mesh_file, prepared_file;
  std::string digest_prefix;  ///< the first 16 hex digits of its mesh_digest, as named
  long long vertices = 0, faces = 0;
};

/// The originals stored in `folder` prepared on `base`, by name (none when the folder is absent).
std::vector<StoredOriginal> stored_originals_in(const std::filesystem::path& folder, BaseSolid base);

struct FoundOriginal {
  PreparedModel model;
  std::filesystem::path mesh_file;
  double mrms_relative = 0;  ///< of `given`, after registration (same_surface.hpp)
};

/// The stored originals `given` is the surface of (re-saved, reordered or moved: the same vertex
/// and face counts, then match_surface), nearest first, each loaded as it was prepared. Empty
/// when `given` is byte for byte one of them (its own preparation is that one) or none.
std::vector<FoundOriginal> find_stored_originals(const Mesh& given, const std::vector<StoredOriginal>& stored,
                                                 const JobControl* control);

}  // namespace meshmark::cli
