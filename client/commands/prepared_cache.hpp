#pragma once
// Prepared originals kept between runs of the CLI, so that a second embed or detect of the same
// original skips its preparation (the parameterization is most of a cold embed). One file per
// mesh digest and grid base, written atomically, its digest and checksum checked on load (a file
// that does not load is removed and prepared again), the least recently used files removed once
// the folder holds more than its bound. The cache is a store only: the caller prepares on a miss.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "core/watermark/prepared_model.hpp"

namespace meshmark::cli {

/// $MESHMARK_CACHE, else $XDG_CACHE_HOME/meshmark, else ~/.cache/meshmark.
std::filesystem::path default_cache_folder();

class PreparedCache {
 public:
  static constexpr std::uintmax_t kDefaultMaxBytes = std::uintmax_t{2} << 30;

  PreparedCache(std::filesystem::path folder, std::uintmax_t max_bytes = kDefaultMaxBytes);
  /// The model prepared earlier from this mesh with this base, or nothing.
  std::optional<PreparedModel> find(const Mesh& mesh, BaseSolid base, const JobControl* control) const;
  /// Keeps `model` (prepared with `base`), then trims the folder to its bound; returns the file
  /// written. A cache that cannot be written is reported on standard error, never an error of the
  /// command (nothing is then returned).
  std::optional<std::filesystem::path> keep(const PreparedModel& model, BaseSolid base) const;
  std::filesystem::path file_for(const std::string& digest, BaseSolid base) const;

 private:
  void trim() const;
  std::filesystem::path folder_;
  std::uintmax_t max_bytes_;
};

/// --cache DIR and --no-cache.
struct CacheArgs {
  std::string folder;  ///< empty: default_cache_folder()
  bool disabled = false;
  void add_to(CLI::App* cmd);
};

/// Where prepare_through_cache found or kept a prepared original.
struct CacheUse {
  bool hit = false;            ///< found in the cache, not prepared now
  std::filesystem::path file;  ///< the cache's file holding its bytes (empty: none)
};

/// The original prepared, from the cache when it holds it, else prepared now and kept there.
PreparedModel prepare_through_cache(const Mesh& mesh, const PrepareOptions& options, const CacheArgs& args,
                                    const JobControl* control, CacheUse& use);

}  // namespace meshmark::cli
