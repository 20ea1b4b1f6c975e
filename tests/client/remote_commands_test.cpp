// `meshmark owners|models|jobs|health` against a real daemon: the command-line side of the API.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "client/remote_client.hpp"
#include "core/io/mesh_document.hpp"
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

  // Runs a remote command; its standard output must be JSON.
  static nlohmann::json run_json(const std::string& arguments, int expected_status = 0) {
    const CliRun run = run_cli(arguments + server());
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
