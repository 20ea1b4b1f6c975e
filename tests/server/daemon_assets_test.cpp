// The real daemon with real assets: the upload kept byte for byte, the marked copy served in the
// original's format (a zipped glTF as the same zip), differing only in positions, and suspects
// read in every format.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/attacks/reorder.hpp"
#include "core/attacks/split_vertices.hpp"
#include "core/io/packaged_document.hpp"
#include "core/io/write_mesh.hpp"
#include "core/io/zip_archive.hpp"
#include "tests/io/document_helpers.hpp"
#include "tests/io/structural_diff.hpp"
#include "tests/server/api_client.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/procedural_assets.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

std::string asset_bytes(const std::string& path) { return file_bytes(named_asset(path).string()); }

class DaemonAssets : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon_ = new DaemonProcess(temp_dir("assets"));
    key_ = ApiClient(daemon_->port(), "").create_owner(DaemonProcess::admin_token(), "studio-assets");
  }
  static void TearDownTestSuite() {
    delete daemon_;
    daemon_ = nullptr;
  }
  ApiClient owner() const { return ApiClient(daemon_->port(), key_); }

  // Embeds a copy for `recipient` and returns (the finished job, the downloaded bytes).
  std::pair<nlohmann::json, ApiResponse> marked_copy(const nlohmann::json& model, const nlohmann::json& request) const {
    const std::string path = "/v1/models/" + model.at("id").get<std::string>();
    const ApiResponse r = owner().post_json(path + "/embed", request);
    EXPECT_EQ(r.status, 202) << r.body;
    const nlohmann::json job = owner().wait_job(r.json().at("job_id").get<std::string>());
    EXPECT_EQ(job.value("state", ""), "succeeded") << job.dump();
    return {job, owner().get("/v1/jobs/" + job.at("id").get<std::string>() + "/result")};
  }

  nlohmann::json detect(const nlohmann::json& model, const std::string& bytes, const std::string& format) const {
    const ApiResponse r =
        owner().post_bytes("/v1/models/" + model.at("id").get<std::string>() + "/detect?format=" + format, bytes);
    EXPECT_EQ(r.status, 202) << r.body;
    const nlohmann::json job = owner().wait_job(r.json().at("job_id").get<std::string>());
    EXPECT_EQ(job.value("state", ""), "succeeded") << job.dump();
    return job.value("result", nlohmann::json::object());
  }

  static DaemonProcess* daemon_;
  static std::string key_;
};

DaemonProcess* DaemonAssets::daemon_ = nullptr;
std::string DaemonAssets::key_;

TEST_F(DaemonAssets, GlbComesBackAsGlbDifferingOnlyInPositionsAndNamesItsRecipient) {
  const std::string original = asset_bytes("procedural/glb");
  const nlohmann::json model = owner().upload_ready(original, "glb", "creature");
  EXPECT_EQ(model.value("vertices", 0), procedural_mesh("creature").V.rows());  // the welded surface
  EXPECT_EQ(model.value("format", ""), "glb");
  const auto [job, download] = marked_copy(model, {{"recipient", "shop-glb"}});
  ASSERT_EQ(download.status, 200);
  EXPECT_EQ(download.header("Content-Type"), "model/gltf-binary");
  EXPECT_EQ(job["result"].value("kept_whole", false), true);
  EXPECT_EQ(difference_outside_positions(original, download.body, MeshFormat::glb), "");
  EXPECT_NE(download.body, original);
  const nlohmann::json found = detect(model, download.body, "glb");
  ASSERT_TRUE(found["match"].is_object()) << found.dump();
  EXPECT_EQ(found["match"].value("recipient", ""), "shop-glb");
}

TEST_F(DaemonAssets, ZippedGltfComesBackAsTheSameZip) {
  const auto [json, bin] = split_glb(asset_bytes("procedural/glb"), "creature.bin");
  const std::string notes = "licence: SCEA Shared Source\n";
  const std::string upload =
      zip_of({{"creature/creature.gltf", json}, {"creature/creature.bin", bin}, {"creature/NOTES.txt", notes}}, false);
  const nlohmann::json model = owner().upload_ready(upload, "gltf", "creature-gltf");
  const auto [job, download] = marked_copy(model, {{"recipient", "shop-zip"}});
  ASSERT_EQ(download.status, 200);
  EXPECT_EQ(download.header("Content-Type"), "application/zip");
  const ZipArchive zip(download.body, 1u << 30, "download");
  ASSERT_EQ(zip.entries().size(), 3u);
  EXPECT_EQ(zip.extract(*zip.find("creature/NOTES.txt")), notes);
  // The .gltf and its buffer, side by side in two folders, differ only in positions.
  const auto before = std::filesystem::path(temp_dir("zip-before")),
             after = std::filesystem::path(temp_dir("zip-after"));
  std::filesystem::create_directories(before);
  std::filesystem::create_directories(after);
  std::ofstream(before / "creature.bin", std::ios::binary) << bin;
  std::ofstream(after / "creature.bin", std::ios::binary) << zip.extract(*zip.find("creature/creature.bin"));
  EXPECT_EQ(difference_outside_positions(json, zip.extract(*zip.find("creature/creature.gltf")), MeshFormat::gltf,
                                         before, after),
            "");
  EXPECT_NE(zip.extract(*zip.find("creature/creature.bin")), bin);
  // A leak re-exported through another tool as OBJ, vertices renumbered and split.
  const Mesh scene = PackagedDocument(download.body, MeshFormat::gltf, {}, "download").document().scene();
  const std::string obj = write_mesh_to_memory(split_vertices(reorder(scene, 2), 0.3, 3), MeshFormat::obj);
  const nlohmann::json found = detect(model, obj, "obj");
  ASSERT_TRUE(found["match"].is_object()) << found.dump();
  EXPECT_EQ(found["match"].value("recipient", ""), "shop-zip");
}

TEST_F(DaemonAssets, AGltfWhoseBufferIsNotSentIsRefusedWithTheZipHint) {
  const auto [json, bin] = split_glb(asset_bytes("procedural/glb"), "creature.bin");
  const ApiResponse r = owner().post_bytes("/v1/models?format=gltf&name=alone", json);
  EXPECT_EQ(r.status, 400);
  EXPECT_TRUE(r.is_problem());
  EXPECT_NE(r.body.find("as a ZIP"), std::string::npos) << r.body;
}

// A ZIP entry that claims to inflate to 3.75 GiB: refused from its header, nothing inflated.
TEST_F(DaemonAssets, AZipBombIsRefusedAsTooLargeBeforeInflating) {
  std::string bomb = zip_of({{"3D/3dmodel.model", "<model/>"}}, false);
  const std::size_t directory = bomb.find("PK\x01\x02");
  ASSERT_NE(directory, std::string::npos);
  for (int i = 0; i < 4; ++i) bomb[directory + 24 + i] = static_cast<char>(i == 3 ? 0xF0 : 0x00);  // uncompressed size
  const ApiResponse r = owner().post_bytes("/v1/models?format=3mf&name=bomb", bomb);
  EXPECT_EQ(r.status, 413) << r.body;
  EXPECT_NE(r.body.find("above the limit"), std::string::npos) << r.body;
  EXPECT_EQ(owner().get("/livez").status, 200);
}

TEST_F(DaemonAssets, ThreeMfAndObjComeBackWhole) {
  for (const auto& [path, format] : {std::pair{"procedural/3mf", "3mf"}, std::pair{"procedural/obj", "obj"}}) {
    const std::string original = asset_bytes(path);
    const nlohmann::json model = owner().upload_ready(original, format, format);
    const auto [job, download] = marked_copy(model, {{"recipient", std::string("shop-") + format}});
    ASSERT_EQ(download.status, 200) << path;
    EXPECT_EQ(difference_outside_positions(original, download.body, *parse_mesh_format(format)), "") << path;
    const nlohmann::json found = detect(model, download.body, format);
    ASSERT_TRUE(found["match"].is_object()) << path << found.dump();
  }
}

TEST_F(DaemonAssets, AnotherFormatIsThePlainSurfaceAndGlbFromAnotherFormatIsRefused) {
  const nlohmann::json model = owner().upload_ready(asset_bytes("procedural/glb"), "glb", "creature-convert");
  const auto [job, download] = marked_copy(model, {{"recipient", "plain"}, {"format", "ply"}});
  EXPECT_EQ(job["result"].value("kept_whole", true), false);
  EXPECT_EQ(download.body.rfind("ply\n", 0), 0u);
  const ApiResponse refused = owner().post_json("/v1/models/" + model.at("id").get<std::string>() + "/embed",
                                                {{"recipient", "x"}, {"format", "3mf"}});
  EXPECT_EQ(refused.status, 400);
  EXPECT_NE(refused.body.find("comes only from a 3mf original"), std::string::npos) << refused.body;
}

}  // namespace
}  // namespace meshmark::test
