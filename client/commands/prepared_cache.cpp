#include "client/commands/prepared_cache.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <system_error>
#include <vector>

#include "core/io/mesh_document.hpp"
#include "core/mesh/mesh_digest.hpp"
#include "core/util/atomic_file.hpp"
#include "core/watermark/prepared_model_io.hpp"

namespace meshmark::cli {

namespace fs = std::filesystem;

fs::path default_cache_folder() {
  if (const char* set = std::getenv("MESHMARK_CACHE"); set && *set) return set;
  if (const char* cache = std::getenv("XDG_CACHE_HOME"); cache && *cache) return fs::path(cache) / "meshmark";
  const char* home = std::getenv("HOME");
  return fs::path(home && *home ? home : ".") / ".cache" / "meshmark";
}

PreparedCache::PreparedCache(fs::path folder, std::uintmax_t max_bytes)
    : folder_(std::move(folder)), max_bytes_(max_bytes) {}

fs::path PreparedCache::file_for(const std::string& digest, BaseSolid base) const {
  return folder_ / (digest + "-" + to_string(base) + ".prepared");
}

std::optional<PreparedModel> PreparedCache::find(const Mesh& mesh, BaseSolid base, const JobControl* control) const {
  const fs::path file = file_for(mesh_digest(mesh), base);
  std::error_code absent;
  if (!fs::is_regular_file(file, absent)) return std::nullopt;
  try {
    PreparedModel model =
        deserialize_prepared_model(read_file_bytes(file, std::size_t{1} << 31), mesh, nullptr, control);
    std::error_code ignored;  // the time of last use, for trim(); a read-only cache still serves
    fs::last_write_time(file, fs::file_time_type::clock::now(), ignored);
    return model;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meshmark: the cached %s does not load (%s); preparing the original again\n",
                 file.string().c_str(), e.what());
    std::error_code ignored;
    fs::remove(file, ignored);
    return std::nullopt;
  }
}

std::optional<fs::path> PreparedCache::keep(const PreparedModel& model, BaseSolid base) const {
  try {
    create_directories_durably(folder_);
    const fs::path file = file_for(model.digest, base);
    write_file_atomically(file, serialize_prepared_model(model));
    trim();
    return file;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meshmark: the prepared original was not cached in %s (%s)\n", folder_.string().c_str(),
                 e.what());
    return std::nullopt;
  }
}

void PreparedCache::trim() const {
  struct Entry {
    fs::path path;
    fs::file_time_type used;
    std::uintmax_t bytes;
  };
  std::vector<Entry> entries;
  std::uintmax_t total = 0;
  for (const auto& e : fs::directory_iterator(folder_)) {
    if (!e.is_regular_file() || e.path().extension() != ".prepared") continue;
    entries.push_back({e.path(), e.last_write_time(), e.file_size()});
    total += entries.back().bytes;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
  // The newest file stays even alone over the bound: it is the one this run just made.
  for (std::size_t i = 0; total > max_bytes_ && i + 1 < entries.size(); ++i) {
    fs::remove(entries[i].path);
    total -= entries[i].bytes;
  }
}

void CacheArgs::add_to(CLI::App* cmd) {
  cmd->add_option("--cache", folder,
                  "Where prepared originals are kept between runs (default: $MESHMARK_CACHE, else "
                  "$XDG_CACHE_HOME/meshmark, else ~/.cache/meshmark; at most 2 GiB)");
  cmd->add_flag("--no-cache", disabled, "Prepare the original anew and keep nothing");
}

PreparedModel prepare_through_cache(const Mesh& mesh, const PrepareOptions& options, const CacheArgs& args,
                                    const JobControl* control, CacheUse& use) {
  use = {};
  if (args.disabled) return prepare_model(mesh, options, control);
  const PreparedCache cache(args.folder.empty() ? default_cache_folder() : fs::path(args.folder));
  if (std::optional<PreparedModel> cached = cache.find(mesh, options.base, control)) {
    use = {true, cache.file_for(cached->digest, options.base)};
    return std::move(*cached);
  }
  PreparedModel model = prepare_model(mesh, options, control);
  use.file = cache.keep(model, options.base).value_or(fs::path());
  return model;
}

}  // namespace meshmark::cli
