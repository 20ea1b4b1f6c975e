#pragma once
// Where tests find the shared meshes (never copied into the repository) and small synthetic ones.

#include <filesystem>
#include <string>

#include "core/mesh/mesh.hpp"
#include "tests/procedural_meshes.hpp"

/// The first statement of a test (or of a fixture's SetUp/SetUpTestSuite) that reads the real
/// meshes: without them the test is skipped, saying why; ctest lists it as skipped.
#define MESHMARK_NEEDS_SHARED()            \
  if (!::meshmark::test::shared_present()) \
  GTEST_SKIP() << "needs the real meshes: " << ::meshmark::test::shared_root() << " is absent (set MESHMARK_SHARED)"

/// The same for a test on the mesh `name` (see named_mesh): only the real meshes need them.
#define MESHMARK_NEEDS_SHARED_FOR(name) \
  if (!::meshmark::test::is_procedural(name)) MESHMARK_NEEDS_SHARED()

namespace meshmark::test {

/// The folder of the real meshes and assets: $MESHMARK_SHARED, else the build's MESHMARK_SHARED
/// (../shared beside the checkout).
std::filesystem::path shared_root();

/// Whether shared_root() holds meshes/ and assets/.
bool shared_present();

/// shared_root()/meshes/`name`; throws when absent (guard the test with MESHMARK_NEEDS_SHARED).
std::filesystem::path shared_mesh(const std::string& name);

/// shared_root()/assets/`relative`: the real assets; throws when absent.
std::filesystem::path shared_asset(const std::string& relative);

/// Reads a shared mesh (cached per process; meshes are immutable).
const Mesh& load_shared(const std::string& name);

/// "procedural/<shape>": procedural_mesh(shape); any other name: load_shared(name).
const Mesh& named_mesh(const std::string& name);

/// Whether named_mesh(name) is made here rather than read from the real meshes.
bool is_procedural(const std::string& name);

}  // namespace meshmark::test
