// `meshmark owners|models|jobs|health` against a real daemon: the command-line side of the API.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "client/remote_client.hpp"
#include "core/io/mesh_document.hpp"
#include "core/io/zip_archive.hpp"
#include "tests/procedural_assets.hpp"
#include "tests/client/cli_runner.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

class DaemonCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { daemon_ = new DaemonProcess(temp_dir("cli")); }
  static void TearDownTestSuite() {
    delete daemon_;
    daemon_ = nullptr;
  }
  static std::string server() { return " --server " + daemon_->url(); }

  // Runs a remote command with --json; its standard output must be JSON.
  static nlohmann::json run_json(const std::string& arguments, int expected_status = 0) {
    const CliRun run = run_cli(arguments + server() + " --json");
    EXPECT_EQ(run.exit_status, expected_status) << arguments << "\n" << run.out;
    return nlohmann::json::parse(run.out);
  }

  static DaemonProcess* daemon_;
};
DaemonProcess* DaemonCli::daemon_ = nullptr;

TEST_F(DaemonCli, OwnerUploadEmbedDetectNamesTheRecipient) {
  const auto owner = run_json(std::string("owners create --name studio --token ") + DaemonProcess::admin_token());
  const std::string key = " --token " + owner.at("api_key").get<std::string>();

  const auto model =
      run_json("models upload " + procedural_file("creature_large").string() + " --name 'bunny & co' --wait" + key);
  EXPECT_EQ(model.value("state", ""), "ready");
  EXPECT_EQ(model.value("name", ""), "bunny & co");  // the name survives the query string
  const std::string id = model.at("id");

  const auto copy_file = temp_dir("cli-copy") / "copy.ply";
  const auto copy =
      run_json("models embed " + id + " --recipient alice --format ply --out " + copy_file.string() + key);
  EXPECT_TRUE(std::filesystem::exists(copy_file));
  EXPECT_EQ(copy.value("recipient", ""), "alice");

  const auto check = run_json("models detect " + id + " " + copy_file.string() + key);
  EXPECT_EQ(check.at("result").value("payload", ""), copy.value("payload", "?"));
  EXPECT_EQ(check.at("result").at("match").value("recipient", ""), "alice");

  const auto embeddings = run_json("models embeddings " + id + key);
  ASSERT_EQ(embeddings.at("embeddings").size(), 1u);
}

// A detection's evidence report, as the console downloads it.
TEST_F(DaemonCli, JobsReportWritesTheDetectionsEvidence) {
  const auto owner = run_json(std::string("owners create --name evidence --token ") + DaemonProcess::admin_token());
  const std::string key = " --token " + owner.at("api_key").get<std::string>();
  const std::string id =
      run_json("models upload " + procedural_file("creature").string() + " --name creature --wait" + key).at("id");
  const auto dir = temp_dir("cli-report");
  run_json("models embed " + id + " --recipient alice --format ply --out " + (dir / "copy.ply").string() + key);
  const auto check = run_json("models detect " + id + " " + (dir / "copy.ply").string() + key);
  const auto file = dir / "evidence.html";
  const auto report = run_json("jobs report " + check.at("id").get<std::string>() + " --out " + file.string() + key);
  EXPECT_EQ(report.value("file", ""), file.string());
  std::ifstream in(file);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("handed out to alice"), std::string::npos);
  EXPECT_EQ(run_cli("jobs report job_none" + key + server()).exit_status == 0, false);
}

// Without --json a remote command answers as the local ones do: one plain line first, the
// details after; detect exits 0 when it finds a mark and 1 when it does not.
TEST_F(DaemonCli, DetectAnswersInOnePlainLineAndExitsOneWhenNothingIsFound) {
  const auto owner = run_json(std::string("owners create --name words --token ") + DaemonProcess::admin_token());
  const std::string key = " --token " + owner.at("api_key").get<std::string>();
  const std::string original = procedural_file("creature").string();
  const std::string id = run_json("models upload " + original + " --name creature --wait" + key).at("id");
  const auto dir = temp_dir("cli-words");
  const CliRun embed = run_cli("models embed " + id + " --recipient 'partner a' --format ply" + key + server(), false,
                               "cd " + dir.string() + " &&");
  ASSERT_EQ(embed.exit_status, 0) << embed.out;
  const auto copy = dir / "creature-partner a.ply";  // named after the model and the recipient
  EXPECT_EQ(embed.out.rfind("wrote creature-partner a.ply: the copy for \"partner a\"", 0), 0u) << embed.out;
  ASSERT_TRUE(std::filesystem::exists(copy));

  const CliRun traced = run_cli("models detect " + id + " '" + copy.string() + "'" + key + server());
  EXPECT_EQ(traced.exit_status, 0) << traced.out;
  EXPECT_NE(traced.out.find(": the copy given to \"partner a\" (payload "), std::string::npos) << traced.out;
  EXPECT_LT(traced.out.find("; chance of coincidence below 1e-"), traced.out.find('\n')) << traced.out;
  EXPECT_NE(traced.out.find("  evidence: "), std::string::npos) << traced.out;

  const CliRun clean = run_cli("models detect " + id + " " + original + key + server());
  EXPECT_EQ(clean.exit_status, 1) << clean.out;
  EXPECT_NE(clean.out.find(": no watermark of this key found"), std::string::npos) << clean.out;
}

// A glTF with its .bin and texture, and an OBJ with its .mtl, go up without zipping by hand; a
// copy of the glTF is traced from its own files; an OBJ whose .mtl is missing is sent with a
// warning naming it.
TEST_F(DaemonCli, AGltfAndAnObjTravelWithTheirFiles) {
  const auto owner = run_json(std::string("owners create --name assets --token ") + DaemonProcess::admin_token());
  const std::string key = " --token " + owner.at("api_key").get<std::string>();
  const auto gltf = procedural_asset("gltf");
  const auto model = run_json("models upload " + gltf.string() + " --name chair --wait" + key);
  EXPECT_EQ(model.value("state", ""), "ready") << model.dump();
  EXPECT_EQ(model.at("packed_with").size(), 2u) << model.dump();  // the .bin and the texture
  const std::string id = model.at("id");
  const auto dir = temp_dir("cli-gltf");
  const auto copy = run_json("models embed " + id + " --recipient bob --out " + (dir / "bob.gltf.zip").string() + key);
  const auto copy_dir = dir / "bob";
  std::filesystem::create_directories(copy_dir);
  const ZipArchive zipped(read_file_bytes(dir / "bob.gltf.zip", 1u << 30), 1u << 30, "copy");
  for (const ZipEntry& e : zipped.entries()) {
    std::filesystem::create_directories((copy_dir / e.name).parent_path());
    std::ofstream(copy_dir / e.name, std::ios::binary) << zipped.extract(e);
  }
  const auto main_file = copy_dir / gltf.filename();
  ASSERT_TRUE(std::filesystem::exists(main_file)) << copy.dump();
  const CliRun traced = run_cli("models detect " + id + " " + main_file.string() + key + server());
  EXPECT_EQ(traced.exit_status, 0) << traced.out;
  EXPECT_NE(traced.out.find("the copy given to \"bob\""), std::string::npos) << traced.out;

  const auto lonely = temp_dir("cli-obj") / "lonely.obj";
  std::filesystem::copy_file(procedural_asset("obj"), lonely);
  const CliRun warned = run_cli("models upload " + lonely.string() + key + server(), true);
  EXPECT_EQ(warned.exit_status, 0) << warned.out;
  EXPECT_NE(warned.out.find("warning: lonely.obj refers to "), std::string::npos) << warned.out;
  EXPECT_NE(warned.out.find(".mtl, which is not beside it"), std::string::npos) << warned.out;
}

// The daemon's copies read on a workstation: the owner's watermark key, exported by the admin,
// is what the local detect needs beside the original. Owner names are unique.
TEST_F(DaemonCli, ACopyOfTheDaemonReadsLocallyWithTheExportedKey) {
  const std::string admin = std::string(" --token ") + DaemonProcess::admin_token();
  const auto owner = run_json("owners create --name workstation" + admin);
  const std::string key = " --token " + owner.at("api_key").get<std::string>();
  const std::string original = procedural_file("creature").string();
  const std::string id = run_json("models upload " + original + " --wait" + key).at("id");
  const auto copy_file = temp_dir("cli-local") / "copy.ply";
  const auto copy = run_json("models embed " + id + " --recipient studio-b --out " + copy_file.string() + key);
  const std::string watermark_key =
      run_json("owners watermark-key " + owner.at("owner_id").get<std::string>() + admin).at("watermark_key");
  EXPECT_EQ(watermark_key.size(), 64u);
  const CliRun local = run_cli("detect " + copy_file.string() + " --original " + original + " --key " + watermark_key);
  EXPECT_EQ(local.exit_status, 0) << local.out;
  EXPECT_NE(local.out.find("marked with this key, payload " + copy.value("payload", "?")), std::string::npos)
      << local.out;
  const CliRun again = run_cli("owners create --name workstation" + admin + server(), true);
  EXPECT_EQ(again.exit_status, 2) << again.out;
  EXPECT_NE(again.out.find("an owner named 'workstation' exists"), std::string::npos) << again.out;
}

// Deleting a model whose copies were handed out is refused without --force: they could never be
// traced again.
TEST_F(DaemonCli, DeletingAModelWithCopiesNeedsForce) {
  const auto owner = run_json(std::string("owners create --name careful --token ") + DaemonProcess::admin_token());
  const std::string key = " --token " + owner.at("api_key").get<std::string>();
  const std::string id = run_json("models upload " + procedural_file("creature").string() + " --wait" + key).at("id");
  run_json("models embed " + id + " --recipient eve --out " + (temp_dir("cli-delete") / "eve.ply").string() + key);
  const CliRun refused = run_cli("models delete " + id + key + server(), true);
  EXPECT_EQ(refused.exit_status, 2) << refused.out;
  EXPECT_NE(refused.out.find("1 copy handed out"), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("--force"), std::string::npos) << refused.out;
  EXPECT_EQ(run_json("models show " + id + key).value("id", ""), id);
  const CliRun forced = run_cli("models delete " + id + " --force" + key + server());
  EXPECT_EQ(forced.exit_status, 0) << forced.out;
  EXPECT_EQ(forced.out, "model " + id + " deleted\n");
}

// `models embed --out x.ply` once wrote OBJ text into x.ply, and `--strength -1` became 0.05.
TEST_F(DaemonCli, EmbedTakesTheFormatFromOutAndTheDaemonJudgesTheStrength) {
  const auto owner = run_json(std::string("owners create --name formats --token ") + DaemonProcess::admin_token());
  const std::string key = " --token " + owner.at("api_key").get<std::string>();
  const std::string id = run_json("models upload " + procedural_file("creature").string() + " --wait" + key).at("id");
  const auto dir = temp_dir("cli-formats");

  const auto ply = dir / "copy.ply";
  run_json("models embed " + id + " --recipient bob --out " + ply.string() + key);
  EXPECT_EQ(read_file_bytes(ply, 1u << 30).substr(0, 4), "ply\n");

  const CliRun negative = run_cli(
      "models embed " + id + " --recipient carol --strength -1 --out " + (dir / "n.obj").string() + key + server(),
      true);
  EXPECT_EQ(negative.exit_status, 2);
  EXPECT_NE(negative.out.find("strength"), std::string::npos) << negative.out;

  const CliRun contradiction = run_cli(
      "models embed " + id + " --recipient dave --format obj --out " + (dir / "c.ply").string() + key + server(), true);
  EXPECT_NE(contradiction.exit_status, 0);
  EXPECT_NE(contradiction.out.find("contradicts"), std::string::npos) << contradiction.out;
  EXPECT_EQ(run_json("models embeddings " + id + key).at("embeddings").size(), 1u) << "only the copy that was made";
}

TEST_F(DaemonCli, TheAdminListsOwnersAndRotatesAKey) {
  const std::string admin = std::string(" --token ") + DaemonProcess::admin_token();
  const auto created = run_json("owners create --name rotating" + admin);
  const std::string id = created.at("owner_id");
  const auto list = run_json("owners list" + admin);
  bool listed = false;
  for (const auto& o : list.at("owners")) listed = listed || o.value("owner_id", "") == id;
  EXPECT_TRUE(listed) << list.dump() << " " << created.dump();
  const auto rotated = run_json("owners rotate-key " + id + admin);
  EXPECT_NE(rotated.value("api_key", ""), created.value("api_key", ""));
  EXPECT_EQ(run_cli("models list --token " + created.at("api_key").get<std::string>() + server(), true).exit_status, 2);
  EXPECT_EQ(run_cli("models list --token " + rotated.at("api_key").get<std::string>() + server()).exit_status, 0);
}

TEST_F(DaemonCli, AnUnreachableDaemonIsExplainedInWords) {
  const CliRun run = run_cli("models list --token x --server http://127.0.0.1:1", true);
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.out.find("nothing answers there"), std::string::npos) << run.out;
}

TEST_F(DaemonCli, AWrongKeyFailsWithTheDaemonsReason) {
  const CliRun run = run_cli("models list --token not-a-key" + server(), true);
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.out.find("401"), std::string::npos) << run.out;
}

TEST_F(DaemonCli, HealthSaysWhetherTheDaemonAnswers) {
  EXPECT_EQ(run_cli("health" + server()).exit_status, 0);
  EXPECT_EQ(run_cli("health --server http://127.0.0.1:1").exit_status, 1);
}

TEST(EncodeQueryValue, KeepsUnreservedCharactersAndEscapesTheRest) {
  EXPECT_EQ(cli::encode_query_value("a-b_c.d~9"), "a-b_c.d~9");
  EXPECT_EQ(cli::encode_query_value("bunny & co/é"), "bunny%20%26%20co%2F%C3%A9");
}

}  // namespace
}  // namespace meshmark::test
