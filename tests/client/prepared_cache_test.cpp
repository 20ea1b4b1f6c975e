#include "client/commands/prepared_cache.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/mesh/mesh_digest.hpp"
#include "core/watermark/watermark.hpp"
#include "tests/client/cli_runner.hpp"
#include "tests/procedural_meshes.hpp"

namespace meshmark::cli {
namespace {

std::filesystem::path fresh_folder(const std::string& name) {
  const auto folder = test::process_temp_folder("prepared-cache") / name;
  std::filesystem::remove_all(folder);
  return folder;
}

// A model served from the cache marks a copy exactly as the model it was made from.
TEST(PreparedCache, AKeptModelIsFoundAndMarksAsTheOriginalDid) {
  const Mesh& mesh = test::procedural_mesh("creature");
  const PreparedModel prepared = prepare_model(mesh);
  const PreparedCache cache(fresh_folder("kept"));
  EXPECT_FALSE(cache.find(mesh, BaseSolid::tetrahedron, nullptr));
  cache.keep(prepared, BaseSolid::tetrahedron);
  const std::optional<PreparedModel> found = cache.find(mesh, BaseSolid::tetrahedron, nullptr);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->digest, prepared.digest);
  EXPECT_FALSE(cache.find(mesh, BaseSolid::octahedron, nullptr));  // another base is another model
  const Bits payload = bits_from_hex("0123456789abcdef");
  EXPECT_TRUE(embed_watermark(*found, "k", payload).mesh.V == embed_watermark(prepared, "k", payload).mesh.V);
}

TEST(PreparedCache, AFileThatDoesNotLoadIsRemovedAndMissed) {
  const Mesh& mesh = test::procedural_mesh("creature");
  const PreparedCache cache(fresh_folder("corrupt"));
  cache.keep(prepare_model(mesh), BaseSolid::tetrahedron);
  const auto file = cache.file_for(mesh_digest(mesh), BaseSolid::tetrahedron);
  std::fstream(file, std::ios::in | std::ios::out | std::ios::binary).seekp(100).put('\x7f');
  EXPECT_FALSE(cache.find(mesh, BaseSolid::tetrahedron, nullptr));
  EXPECT_FALSE(std::filesystem::exists(file));
}

// Over its bound the cache drops the least recently used files, and keeps the newest.
TEST(PreparedCache, OverItsBoundTheLeastRecentlyUsedGo) {
  const Mesh& creature = test::procedural_mesh("creature");
  const Mesh& torus = test::procedural_mesh("torus");
  const auto folder = fresh_folder("bounded");
  const PreparedCache unbounded(folder);
  unbounded.keep(prepare_model(creature), BaseSolid::tetrahedron);
  const auto creature_file = unbounded.file_for(mesh_digest(creature), BaseSolid::tetrahedron);
  const PreparedCache bounded(folder, std::filesystem::file_size(creature_file) + 1);
  bounded.keep(prepare_model(torus), BaseSolid::tetrahedron);
  EXPECT_FALSE(std::filesystem::exists(creature_file));
  EXPECT_TRUE(bounded.find(torus, BaseSolid::tetrahedron, nullptr));
}

// The CLI: a second embed of one original loads it prepared, and its copy is the same file.
TEST(PreparedCache, ASecondEmbedOfAnOriginalIsWarmAndWritesTheSameCopy) {
  const std::string original = test::procedural_file("creature").string();
  const auto folder = fresh_folder("cli");
  std::vector<std::string> copies, states;
  for (const char* name : {"first.ply", "second.ply"}) {
    copies.push_back((folder / name).string());
    const test::CliRun run =
        test::run_cli("embed " + original + " " + copies.back() +
                      " --key k --payload 0123456789abcdef --json --cache " + (folder / "cache").string());
    ASSERT_EQ(run.exit_status, 0) << run.out;
    states.push_back(nlohmann::json::parse(run.out).at("cache"));
  }
  EXPECT_EQ(states, (std::vector<std::string>{"miss", "hit"}));
  std::ifstream a(copies[0], std::ios::binary), b(copies[1], std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}));
  const test::CliRun off = test::run_cli("embed " + original + " " + (folder / "third.ply").string() +
                                             " --key k --payload 0123456789abcdef --json --no-cache",
                                         false, "MESHMARK_CACHE=" + (folder / "unused").string());
  ASSERT_EQ(off.exit_status, 0) << off.out;
  EXPECT_EQ(nlohmann::json::parse(off.out).at("cache"), "off");
  EXPECT_FALSE(std::filesystem::exists(folder / "unused"));
}

// The records keep the original as prepared: the cache's file itself, linked, not a second
// serialization of the model; the copy reads against it.
TEST(PreparedCache, TheRecordsLinkTheCachedPreparedOriginal) {
  const std::string original = test::procedural_file("creature").string();
  const auto folder = fresh_folder("linked");
  const std::string copy = (folder / "copy.ply").string();
  const test::CliRun run =
      test::run_cli("embed " + original + " " + copy + " --key k --payload 0123456789abcdef --json --cache " +
                    (folder / "cache").string() + " --records " + (folder / "records").string());
  ASSERT_EQ(run.exit_status, 0) << run.out;
  std::vector<std::filesystem::path> prepared;
  for (const auto* sub : {"cache", "records"})
    for (const auto& e : std::filesystem::directory_iterator(folder / sub))
      if (e.path().extension() == ".prepared") prepared.push_back(e.path());
  ASSERT_EQ(prepared.size(), 2u);
  EXPECT_TRUE(std::filesystem::equivalent(prepared[0], prepared[1]));
  const std::string record = nlohmann::json::parse(run.out).at("record");
  const test::CliRun detect = test::run_cli("detect " + copy + " --record " + record + " --key k --json");
  ASSERT_EQ(detect.exit_status, 0) << detect.out;
  EXPECT_EQ(nlohmann::json::parse(detect.out).at("ber"), 0.0);
}

}  // namespace
}  // namespace meshmark::cli
