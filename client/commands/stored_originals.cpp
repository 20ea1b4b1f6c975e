#include "client/commands/stored_originals.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>

#include "core/io/mesh_document.hpp"
#include "core/io/read_mesh.hpp"
#include "core/mesh/mesh_digest.hpp"
#include "core/registration/same_surface.hpp"
#include "core/watermark/prepared_model_io.hpp"

namespace meshmark::cli {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kStem = "meshmark-original-";
constexpr std::size_t kDigestPrefix = 16;

// The counts a stored original's PLY header declares (embed writes them); false when it has none.
bool read_ply_counts(const fs::path& file, long long& vertices, long long& faces) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  vertices = faces = -1;
  for (int lines = 0; lines < 32 && std::getline(in, line) && line != "end_header"; ++lines) {
    std::istringstream words(line);
    std::string keyword, element;
    long long count = -1;
    if (!(words >> keyword >> element >> count) || keyword != "element") continue;
    if (element == "vertex") vertices = count;
    if (element == "face") faces = count;
  }
  return vertices > 0 && faces > 0;
}

// "meshmark-original-<16 hex>-<base>.ply" names a stored original of that base.
bool names_stored_original(const fs::path& file, BaseSolid base, std::string& digest_prefix) {
  const std::string name = file.filename().string();
  const std::string suffix = "-" + to_string(base) + ".ply";
  if (name.size() != kStem.size() + kDigestPrefix + suffix.size() || !name.starts_with(kStem) ||
      !name.ends_with(suffix))
    return false;
  digest_prefix = name.substr(kStem.size(), kDigestPrefix);
  return true;
}

// The stored original as prepared, when `given` is its surface.
std::optional<FoundOriginal> load_if_same_surface(const Mesh& given, const StoredOriginal& s,
                                                  const JobControl* control) {
  const Mesh mesh = read_mesh(s.mesh_file).mesh;
  const SurfaceMatch match = match_surface(given, RegistrationTarget(mesh), control);
  if (!match.same) return std::nullopt;
  return FoundOriginal{
      deserialize_prepared_model(read_file_bytes(s.prepared_file, std::size_t{1} << 31), mesh, nullptr, control),
      s.mesh_file, match.mrms_relative};
}

}  // namespace

std::string stored_original_stem(const std::string& digest, BaseSolid base) {
  return std::string(kStem) + digest.substr(0, kDigestPrefix) + "-" + to_string(base);
}

std::vector<StoredOriginal> stored_originals_in(const fs::path& folder, BaseSolid base) {
  std::vector<StoredOriginal> stored;
  std::error_code absent;
  for (const auto& entry : fs::directory_iterator(folder, absent)) {
    StoredOriginal s;
    if (!entry.is_regular_file() || !names_stored_original(entry.path(), base, s.digest_prefix)) continue;
    s.mesh_file = entry.path();
    s.prepared_file = fs::path(entry.path()).replace_extension(".prepared");
    if (fs::is_regular_file(s.prepared_file) && read_ply_counts(s.mesh_file, s.vertices, s.faces))
      stored.push_back(std::move(s));
  }
  std::sort(stored.begin(), stored.end(),
            [](const StoredOriginal& a, const StoredOriginal& b) { return a.mesh_file < b.mesh_file; });
  return stored;
}

std::vector<FoundOriginal> find_stored_originals(const Mesh& given, const std::vector<StoredOriginal>& stored,
                                                 const JobControl* control) {
  const std::string digest = mesh_digest(given).substr(0, kDigestPrefix);
  if (std::any_of(stored.begin(), stored.end(), [&](const StoredOriginal& s) { return s.digest_prefix == digest; }))
    return {};
  std::vector<FoundOriginal> found;
  for (const StoredOriginal& s : stored) {
    if (s.vertices != given.V.rows() || s.faces != given.F.rows()) continue;
    try {
      if (std::optional<FoundOriginal> f = load_if_same_surface(given, s, control)) found.push_back(std::move(*f));
    } catch (const Canceled&) {
      throw;
    } catch (const TimeLimitExceeded&) {
      throw;
    } catch (const std::runtime_error& e) {  // a damaged store is reported, and the search goes on
      std::fprintf(stderr, "meshmark: the stored original %s does not load (%s)\n", s.mesh_file.string().c_str(),
                   e.what());
    }
  }
  std::sort(found.begin(), found.end(),
            [](const FoundOriginal& a, const FoundOriginal& b) { return a.mrms_relative < b.mrms_relative; });
  return found;
}

}  // namespace meshmark::cli
