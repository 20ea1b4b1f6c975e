// `meshmark embed` on real assets: the marked copy in the original's format with its companion
// files, nothing of the original overwritten, and plain conversions said as such.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>
#include <nlohmann/json.hpp>

#include "core/io/mesh_document.hpp"
#include "tests/build_paths.hpp"
#include "tests/client/cli_runner.hpp"
#include "tests/io/document_helpers.hpp"
#include "tests/io/structural_diff.hpp"
#include "tests/procedural_assets.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

namespace fs = std::filesystem;

fs::path fresh_folder(const std::string& name) {
  const auto dir = test::process_temp_folder("meshmark-embed") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string bytes_of(const fs::path& p) { return read_file_bytes(p, 1u << 30); }

const std::string kMark = " --key k1 --payload 0123456789abcdef";

// The creature's .glb as a .gltf with its buffer in creature.bin beside it: a glTF with a
// companion file.
fs::path creature_as_gltf(const fs::path& folder) {
  const auto [json, bin] = test::split_glb(bytes_of(test::procedural_asset("glb")), "creature.bin");
  std::ofstream(folder / "creature.gltf") << json;
  std::ofstream(folder / "creature.bin", std::ios::binary) << bin;
  return folder / "creature.gltf";
}

// The welded surface of the procedural assets: the creature, its seam's split vertices joined.
long creature_vertices() { return static_cast<long>(test::procedural_mesh("creature").V.rows()); }

TEST(EmbedAssets, GlbComesBackAsGlbDifferingOnlyInPositions) {
  const fs::path out = fresh_folder("glb") / "creature_marked.glb";
  const fs::path in = test::procedural_asset("glb");
  const test::CliRun run = test::run_cli("embed " + in.string() + " " + out.string() + kMark + " --json");
  ASSERT_EQ(run.exit_status, 0) << run.out;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["kept_whole"], true);
  EXPECT_EQ(j["document"]["format"], "glb");
  EXPECT_EQ(j["document"]["welded"]["vertices"], creature_vertices());
  EXPECT_EQ(test::difference_outside_positions(in, out), "");
  const test::CliRun detect = test::run_cli("detect " + out.string() + " --original " + in.string() +
                                            " --key k1 --expect 0123456789abcdef --json");
  ASSERT_EQ(detect.exit_status, 0) << detect.out;
  EXPECT_EQ(nlohmann::json::parse(detect.out)["ber"], 0.0);
}

TEST(EmbedAssets, GltfBufferIsWrittenUnderTheOutputsNameAndTheOriginalIsUntouched) {
  const fs::path in = creature_as_gltf(fresh_folder("gltf-in"));
  const std::string bin_before = bytes_of(in.parent_path() / "creature.bin");
  const fs::path out =
      in.parent_path() / "creature_marked.gltf";  // the same folder: the buffer must not be overwritten
  const test::CliRun run = test::run_cli("embed " + in.string() + " " + out.string() + kMark);
  ASSERT_EQ(run.exit_status, 0) << run.out;
  EXPECT_EQ(bytes_of(in.parent_path() / "creature.bin"), bin_before);
  ASSERT_TRUE(fs::exists(in.parent_path() / "creature_marked.bin"));
  EXPECT_EQ(nlohmann::json::parse(bytes_of(out))["buffers"][0]["uri"], "creature_marked.bin");
  EXPECT_EQ(test::difference_outside_positions(in, out), "");
}

// What is handed out is the copy alone: no unmarked buffer, no original, no record.
TEST(EmbedAssets, TheOutputFolderHoldsTheCopyAndWhatItRefersToAndNothingOfTheOriginal) {
  const fs::path in = creature_as_gltf(fresh_folder("gltf-clean-in"));
  const fs::path folder = fresh_folder("gltf-clean-out");
  const test::CliRun run =
      test::run_cli("embed " + in.string() + " " + (folder / "creature_marked.gltf").string() + kMark);
  ASSERT_EQ(run.exit_status, 0) << run.out;
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.insert(entry.path().filename().string());
    for (const auto& original : fs::directory_iterator(in.parent_path()))
      EXPECT_NE(bytes_of(entry.path()), bytes_of(original.path()))
          << entry.path() << " is a copy of the original's " << original.path();
  }
  EXPECT_EQ(names, (std::set<std::string>{"creature_marked.gltf", "creature_marked.bin"}));
}

TEST(EmbedAssets, ObjInAnotherFolderTakesItsMaterialAndTextureAlong) {
  const fs::path in = test::procedural_asset("obj");
  const fs::path out = fresh_folder("obj") / "creature.obj";
  const test::CliRun run = test::run_cli("embed " + in.string() + " " + out.string() + kMark);
  ASSERT_EQ(run.exit_status, 0) << run.out;
  for (const char* companion : {"creature.mtl", "texture.png"})
    EXPECT_EQ(bytes_of(out.parent_path() / companion), bytes_of(in.parent_path() / companion)) << companion;
  EXPECT_EQ(test::difference_outside_positions(in, out), "");
}

TEST(EmbedAssets, ThreeMfKeepsEveryOtherPartOfItsPackage) {
  const fs::path in = test::procedural_asset("3mf");
  const fs::path out = fresh_folder("3mf") / "creature.3mf";
  ASSERT_EQ(test::run_cli("embed " + in.string() + " " + out.string() + kMark).exit_status, 0);
  EXPECT_EQ(test::difference_outside_positions(in, out), "");
}

TEST(EmbedAssets, WritingOverTheOriginalIsRefused) {
  const fs::path in = creature_as_gltf(fresh_folder("overwrite"));
  const std::string before = bytes_of(in);
  const test::CliRun run = test::run_cli("embed " + in.string() + " " + in.string() + kMark, true);
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.out.find("overwrite the original"), std::string::npos) << run.out;
  EXPECT_EQ(bytes_of(in), before);
}

TEST(EmbedAssets, AnotherFormatIsAPlainMeshAndSaysSo) {
  const fs::path in = test::procedural_asset("glb");
  const fs::path folder = fresh_folder("convert");
  const test::CliRun run = test::run_cli("embed " + in.string() + " " + (folder / "creature.ply").string() + kMark);
  ASSERT_EQ(run.exit_status, 0) << run.out;
  EXPECT_NE(run.out.find("plain ply mesh"), std::string::npos) << run.out;
  const test::CliRun refused =
      test::run_cli("embed " + in.string() + " " + (folder / "creature.3mf").string() + kMark, true);
  EXPECT_EQ(refused.exit_status, 2);
  EXPECT_NE(refused.out.find("comes only from a 3mf original"), std::string::npos) << refused.out;
}

TEST(EmbedAssets, AnAssetTooSmallForThePayloadIsRefusedWithTheReasonAndNothingIsWritten) {
  MESHMARK_NEEDS_SHARED();
  const auto out = fresh_folder("refused") / "a.gltf";
  const test::CliRun run = test::run_cli(
      "embed " + test::named_asset("Avocado/glTF/Avocado.gltf").string() + " " + out.string() + kMark, true);
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.out.find("too few vertices (363)"), std::string::npos) << run.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// An instanced mesh is marked in every instance (they share its stored positions), and the copy,
// every instance drawn, reads back from its record.
TEST(EmbedAssets, AnInstancedMeshCarriesTheMarkInEveryInstanceAndTheCopyReadsBack) {
  MESHMARK_NEEDS_SHARED();
  const auto out = fresh_folder("instanced") / "truck.glb";
  const test::CliRun run =
      test::run_cli("embed " + test::named_asset("CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb").string() + " " +
                    out.string() + kMark + " --json");
  ASSERT_EQ(run.exit_status, 0) << run.out;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_GE(j["further_instances"].get<int>(), 1);
  EXPECT_TRUE(j["verification"]["passed"].get<bool>());
  const test::CliRun detect = test::run_cli("detect " + out.string() + " --key k1 --record " +
                                            test::record_of(out.string(), "0123456789abcdef") + " --json");
  ASSERT_EQ(detect.exit_status, 0) << detect.out;
  const nlohmann::json d = nlohmann::json::parse(detect.out);
  EXPECT_EQ(d["payload"], "0123456789abcdef");
  EXPECT_EQ(d["ber"], 0.0);
}

// Nearly symmetric shapes fit about as well turned: registration searches the turns their
// principal axes cannot tell apart, and reads every pose that fits. A turned copy reads back.
TEST(EmbedAssets, NearlySymmetricAssetsAreMarkedAndATurnedCopyReadsBack) {
  MESHMARK_NEEDS_SHARED();
  for (const char* name : {"WaterBottle-Draco/glTF-Draco/WaterBottle.gltf", "sword-obj/UV.obj"}) {
    const fs::path in = test::named_asset(name);
    const auto out = fresh_folder("symmetric") / ("marked" + in.extension().string());
    const test::CliRun run = test::run_cli("embed " + in.string() + " " + out.string() + kMark + " --json");
    ASSERT_EQ(run.exit_status, 0) << name << ": " << run.out;
    EXPECT_TRUE(nlohmann::json::parse(run.out)["verification"]["passed"].get<bool>()) << name;
    const std::string turned = (out.parent_path() / "turned.ply").string();
    ASSERT_EQ(test::run_cli("attack similarity --seed 5 " + out.string() + " " + turned).exit_status, 0);
    const test::CliRun detect = test::run_cli("detect " + turned + " --key k1 --record " +
                                              test::record_of(out.string(), "0123456789abcdef") + " --json");
    ASSERT_EQ(detect.exit_status, 0) << detect.out;
    const nlohmann::json d = nlohmann::json::parse(detect.out);
    EXPECT_EQ(d["payload"], "0123456789abcdef") << name;
    EXPECT_EQ(d["ber"], 0.0) << name;
  }
}

TEST(InfoCommand, ReportsThePartsAndTheWeldedSurfaceOfAnAsset) {
  MESHMARK_NEEDS_SHARED();
  const test::CliRun run =
      test::run_cli("info --json " + test::named_asset("CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb").string());
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["document"]["format"], "glb");
  ASSERT_GE(j["document"]["parts"].size(), 2u);
  std::size_t instanced = 0;
  for (const auto& p : j["document"]["parts"]) instanced += p["instances"].get<std::size_t>() > 1;
  EXPECT_GE(instanced, 1u);
  EXPECT_LT(j["document"]["welded"]["vertices"].get<long>(), j["document"]["stored_vertices"].get<long>());
  const test::CliRun text = test::run_cli("info " + test::procedural_asset("glb").string());
  EXPECT_NE(text.out.find("stored vertices -> " + std::to_string(creature_vertices())), std::string::npos) << text.out;
}

}  // namespace
}  // namespace meshmark

namespace meshmark {
namespace {

namespace fs = std::filesystem;

// What a shell command prints on its standard output.
std::string output_of(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "";
  std::string out;
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  pclose(pipe);
  return out;
}

// The glTF assets marked: the procedural ones always, the shared ones when present.
std::vector<fs::path> gltf_originals() {
  std::vector<fs::path> originals = {test::procedural_asset("glb"), test::procedural_asset("gltf"),
                                     test::procedural_asset("skinned-glb")};
  if (!test::shared_present()) {
    std::printf("the shared glTF assets are absent: validating the procedural ones only\n");
    return originals;
  }
  for (const auto& entry : fs::recursive_directory_iterator(test::shared_root() / "assets"))
    if (entry.path().extension() == ".gltf" || entry.path().extension() == ".glb") originals.push_back(entry.path());
  return originals;
}

// The Khronos validator (npm gltf-validator) finds no error in a marked glTF whose original has none.
TEST(GltfValidator, MarkedCopiesAreValidWheneverTheirOriginalsAre) {
  const char* modules = std::getenv("MESHMARK_NODE_MODULES");
  if (!modules || !fs::exists(fs::path(modules) / "gltf-validator"))
    GTEST_SKIP() << "the glTF validator is not installed (deploy/install-node-tools.sh sets MESHMARK_NODE_MODULES)";
  const std::string validate =
      "NODE_PATH='" + std::string(modules) + "' node " + test::source_dir() + "/tests/tools/validate_gltf.js";
  int compared = 0;
  for (const fs::path& original : gltf_originals()) {
    const fs::path out =
        fresh_folder("validated-" + std::to_string(compared)) / ("marked" + original.extension().string());
    const test::CliRun embed =
        test::run_cli("embed '" + original.string() + "' " + out.string() + " --key k1 --payload c0de --quiet", true);
    if (embed.exit_status != 0) {  // a refusal, with its reason: nothing to validate
      std::printf("%s: refused (%s)\n", original.filename().c_str(), embed.out.c_str());
      continue;
    }
    std::istringstream lines(output_of(validate + " '" + original.string() + "' " + out.string()));
    std::string line;
    std::vector<nlohmann::json> reports;
    while (std::getline(lines, line)) reports.push_back(nlohmann::json::parse(line));
    ASSERT_EQ(reports.size(), 2u) << original;
    ASSERT_FALSE(reports[1].contains("failure")) << reports[1].dump();
    if (original.string().find("meshmark-assets") != std::string::npos) {  // made by the tests: valid
      EXPECT_EQ(reports[0].value("errors", -1), 0) << reports[0].dump(1);
    }
    if (reports[0].value("errors", 1) == 0) {
      EXPECT_EQ(reports[1].value("errors", -1), 0) << reports[1].dump(1);
    }
    ++compared;
  }
  EXPECT_GE(compared, 2) << "the procedural assets, at least, were marked and validated";
}

}  // namespace
}  // namespace meshmark
