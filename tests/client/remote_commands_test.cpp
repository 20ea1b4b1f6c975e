// `meshmark owners|models|jobs|health` against a real daemon: the command-line side of the API.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "client/remote_client.hpp"
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

  const auto model = run_json("models upload " + shared_mesh("bunny.obj").string() + " --name 'bunny & co' --wait" + key);
  EXPECT_EQ(model.value("state", ""), "ready");
  EXPECT_EQ(model.value("name", ""), "bunny & co");  // the name survives the query string
  const std::string id = model.at("id");

  const auto copy_file = temp_dir("cli-copy") / "copy.ply";
  const auto copy = run_json("models embed " + id + " --recipient alice --format ply --out " + copy_file.string() + key);
  EXPECT_TRUE(std::filesystem::exists(copy_file));
  EXPECT_EQ(copy.value("recipient", ""), "alice");

  const auto check = run_json("models detect " + id + " " + copy_file.string() + key);
  EXPECT_EQ(check.at("result").value("payload", ""), copy.value("payload", "?"));
  EXPECT_EQ(check.at("result").at("match").value("recipient", ""), "alice");

  const auto embeddings = run_json("models embeddings " + id + key);
  ASSERT_EQ(embeddings.at("embeddings").size(), 1u);
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
