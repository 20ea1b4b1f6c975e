#include "tests/test_data.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>
#include <stdexcept>

#include "core/io/read_mesh.hpp"
#include "tests/build_paths.hpp"

namespace meshmark::test {

std::filesystem::path shared_root() {
  const char* env = std::getenv("MESHMARK_SHARED");
  return env && *env ? std::filesystem::path(env) : std::filesystem::path(configured_shared_root());
}

bool shared_present() {
  static const bool present = std::filesystem::is_directory(shared_root() / "meshes") &&
                              std::filesystem::is_directory(shared_root() / "assets");
  return present;
}

namespace {

std::filesystem::path shared_file(const std::filesystem::path& relative) {
  const auto path = shared_root() / relative;
  if (!std::filesystem::exists(path))
    throw std::runtime_error("real test data not found: " + path.string() +
                             " (set MESHMARK_SHARED to the folder holding meshes/ and assets/, and start the test "
                             "with MESHMARK_NEEDS_SHARED() so that it is skipped without them)");
  return path;
}

}  // namespace

std::filesystem::path shared_mesh(const std::string& name) {
  return shared_file(std::filesystem::path("meshes") / name);
}

std::filesystem::path shared_asset(const std::string& relative) {
  return shared_file(std::filesystem::path("assets") / relative);
}

const Mesh& load_shared(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, Mesh> cache;
  std::lock_guard lock(mutex);
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, read_mesh(shared_mesh(name)).mesh).first;
  return it->second;
}

bool is_procedural(const std::string& name) { return name.rfind("procedural/", 0) == 0; }

const Mesh& named_mesh(const std::string& name) {
  return is_procedural(name) ? procedural_mesh(name.substr(std::string("procedural/").size())) : load_shared(name);
}

}  // namespace meshmark::test
