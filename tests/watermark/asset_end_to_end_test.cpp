// The watermark on the real assets big enough to carry a 64-bit payload (three on the sphere, three
// on bumps), each in its own format: marked as `meshmark embed` marks it (the document read, its welded surface marked,
// the file written back whole), then what a leaker does to an asset — re-export through another
// tool (vertices renumbered and split, written as OBJ), Draco compression at 11 to 14 bits,
// 16-bit quantization — and detection from the files.
// Each asset runs as one ctest entry (see tests/CMakeLists.txt): it is marked once.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <memory>
#include <mutex>

#include "core/attacks/draco_compress.hpp"
#include "core/attacks/quantize.hpp"
#include "core/attacks/reorder.hpp"
#include "core/attacks/split_vertices.hpp"
#include "core/io/document_surface.hpp"
#include "core/io/write_mesh.hpp"
#include "core/mesh/weld_positions.hpp"
#include "core/watermark/watermark.hpp"
#include "tests/io/structural_diff.hpp"
#include "tests/test_data.hpp"
#include "tests/watermark/end_to_end_secrets.hpp"

namespace meshmark {
namespace {

struct MarkedAsset {
  std::filesystem::path original, marked;  // the marked copy's main file, in a folder of its own
  PreparedModel model;
  std::unique_ptr<RegistrationTarget> target;
};

const std::map<std::string, std::string>& assets() {
  static const std::map<std::string, std::string> paths = {
      {"Duck", "Duck/glTF-Binary/Duck.glb"},
      {"spot_cow", "spot-cow-obj/cow.obj"},
      {"sphere_logo", "sphere_logo-3mf/sphere_logo.3mf"},
      // Holes, parts, pinches: marked on bumps.
      {"WaterBottle", "WaterBottle-Draco/glTF-Draco/WaterBottle.gltf"},
      {"sword_uv", "sword-obj/UV.obj"},
      {"frag_115", "frag115-ply/frag_115.ply"},
  };
  return paths;
}

const MarkedAsset& marked_asset(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<MarkedAsset>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[name];
  if (slot) return *slot;
  slot = std::make_unique<MarkedAsset>();
  slot->original = test::shared_asset(assets().at(name));
  const auto document = read_document_file(slot->original);
  const WeldedSurface surface = document_surface(*document);
  slot->model = prepare_model(surface.mesh);
  slot->target = std::make_unique<RegistrationTarget>(slot->model.outward_mesh());
  const EmbedResult embedded = embed_watermark(slot->model, test::kEndToEndKey, test::end_to_end_payload());
  const MovedSlots moved = move_slots(*document, surface, embedded.mesh.V);
  const auto folder = std::filesystem::temp_directory_path() / ("meshmark-asset-" + name);
  std::filesystem::create_directories(folder);
  slot->marked = folder / slot->original.filename();
  for (const auto& [file, bytes] : document->write(moved.positions, moved.rotations))
    std::ofstream(file.empty() ? slot->marked : folder / file, std::ios::binary) << bytes;
  return *slot;
}

DetectResult detect(const MarkedAsset& m, const Mesh& suspect) {
  return test::detect_end_to_end(m.model, *m.target, suspect);
}

// The marked file as a leaker has it: its whole scene.
Mesh leaked(const MarkedAsset& m) { return read_document_file(m.marked)->scene(); }

void expect_read_without_errors(const DetectResult& r, const std::string& what) {
  EXPECT_TRUE(r.detected) << what << ": p " << r.p_value;
  ASSERT_TRUE(r.ber.has_value()) << what;
  EXPECT_EQ(*r.ber, 0.0) << what;
}

class AssetEndToEnd : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { MESHMARK_NEEDS_SHARED(); }
};

TEST_P(AssetEndToEnd, TheMarkedFileDiffersOnlyInPositions) {
  const MarkedAsset& m = marked_asset(GetParam());
  EXPECT_EQ(test::difference_outside_positions(m.original, m.marked), "");
}

TEST_P(AssetEndToEnd, TheMarkedFileIsReadWithoutErrors) {
  const MarkedAsset& m = marked_asset(GetParam());
  const Mesh scene = leaked(m);
  expect_read_without_errors(detect(m, weld_positions(scene.V, scene.F).mesh), "as written");
}

TEST_P(AssetEndToEnd, AReExportWithVerticesRenumberedAndSplitIsRead) {
  const MarkedAsset& m = marked_asset(GetParam());
  const Mesh exported = split_vertices(reorder(leaked(m), 3), 0.3, 5);
  const auto obj = m.marked.parent_path() / "reexported.obj";
  write_mesh(obj, exported);
  expect_read_without_errors(detect(m, read_surface(obj)), "re-exported as OBJ");
}

TEST_P(AssetEndToEnd, DracoCompressionIsRead) {
  const MarkedAsset& m = marked_asset(GetParam());
  const std::vector<int> bits = GetParam() == "Duck" ? std::vector<int>{11, 12, 13, 14} : std::vector<int>{14};
  for (const int b : bits)
    expect_read_without_errors(detect(m, draco_compress(leaked(m), b)), "Draco " + std::to_string(b) + " bits");
}

TEST_P(AssetEndToEnd, SixteenBitQuantizationIsRead) {
  const MarkedAsset& m = marked_asset(GetParam());
  expect_read_without_errors(detect(m, quantize(leaked(m), 16)), "16-bit positions");
}

INSTANTIATE_TEST_SUITE_P(Assets, AssetEndToEnd,
                         ::testing::Values("Duck", "spot_cow", "sphere_logo", "WaterBottle", "sword_uv", "frag_115"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace meshmark
