// A copy for every recipient in one step, through the API and the command line, each copy
// traced back to its recipient (twelve detections: release build only).

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "core/attacks/similarity_transform.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"
#include "core/io/zip_archive.hpp"
#include "core/mesh/example_shapes.hpp"
#include "tests/client/cli_runner.hpp"
#include "tests/server/api_client.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

class DaemonBatch : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon_ = new DaemonProcess(temp_dir("batch"));
    const OwnerWithModel made = owner_with_creature(daemon_->port(), "batch-studio");
    key_ = made.key;
    model_ = made.model;
  }
  static void TearDownTestSuite() {
    delete daemon_;
    daemon_ = nullptr;
  }
  static std::string connection() { return " --server " + daemon_->url() + " --token " + key_; }
  static ApiClient owner() { return ApiClient(daemon_->port(), key_); }

  static DaemonProcess* daemon_;
  static std::string key_, model_;
};
DaemonProcess* DaemonBatch::daemon_ = nullptr;
std::string DaemonBatch::key_;
std::string DaemonBatch::model_;

TEST_F(DaemonBatch, TwelveRecipientsFromAFileGetACopyEachAndEachIsTracedToItsRecipient) {
  const auto dir = temp_dir("batch-cli");
  std::ofstream(dir / "partners.csv") << "recipient,contact\npartner-01,a@x\n# paused\n"
                                      << "partner-02,b@x\npartner-03\npartner-04\npartner-05\npartner-06\npartner-07\n"
                                      << "partner-08\npartner-09\npartner-10\npartner-11\n\"partner 12\",c@x\n";
  const CliRun made = run_cli("models embed " + model_ + " --recipients-file " + (dir / "partners.csv").string() +
                              " --format ply --requested-by 'Ana L' --out " + (dir / "copies").string() + connection());
  ASSERT_EQ(made.exit_status, 0) << made.out;
  EXPECT_EQ(made.out.rfind("wrote 12 of 12 copies into " + (dir / "copies").string(), 0), 0u) << made.out;
  std::set<std::string> payloads;
  for (int k = 1; k <= 12; ++k) {
    const std::string recipient =
        k == 12 ? "partner 12" : "partner-" + std::string(k < 10 ? "0" : "") + std::to_string(k);
    const auto copy = dir / "copies" / ("creature-" + recipient + ".ply");
    ASSERT_TRUE(std::filesystem::exists(copy)) << copy << "\n" << made.out;
    const CliRun traced = run_cli("models detect " + model_ + " '" + copy.string() + "' --json" + connection());
    ASSERT_EQ(traced.exit_status, 0) << traced.out;
    const auto match = nlohmann::json::parse(traced.out)["result"]["match"];
    EXPECT_EQ(match.value("recipient", ""), recipient) << traced.out;
    payloads.insert(match.value("payload", ""));
  }
  EXPECT_EQ(payloads.size(), 12u) << "a payload of its own for each";
  const auto exported = owner().get("/v1/embeddings").json()["embeddings"];
  EXPECT_EQ(exported.size(), 12u);
  for (const auto& copy : exported) EXPECT_EQ(copy.value("requested_by", ""), "Ana L") << copy.dump();
}

// The API takes the whole list in one request or none of it; the copies it accepts are listed.
TEST_F(DaemonBatch, TheApiTakesAListOfRecipientsWholeAndRefusesABadOneWhole) {
  std::vector<std::string> names;
  for (int k = 0; k < 12; ++k) names.push_back("api-" + std::to_string(k));
  const ApiResponse accepted =
      owner().post_json("/v1/models/" + model_ + "/embed", {{"recipients", names}, {"format", "ply"}});
  ASSERT_EQ(accepted.status, 202) << accepted.body;
  const auto copies = accepted.json().at("copies");
  ASSERT_EQ(copies.size(), 12u);
  for (std::size_t k = 0; k < copies.size(); ++k) {
    EXPECT_EQ(copies[k].value("recipient", ""), names[k]);
    EXPECT_EQ(owner().wait_job(copies[k].value("job_id", "")).value("state", ""), "succeeded") << copies[k].dump();
  }
  std::string only_these = "?";
  for (const std::string& n : names) only_these += "recipient=" + n + "&";
  const ApiResponse zipped = owner().get("/v1/models/" + model_ + "/copies.zip" + only_these);
  ASSERT_EQ(zipped.status, 200) << zipped.body;
  EXPECT_EQ(zipped.header("Content-Type"), "application/zip");
  const ZipArchive all(zipped.body, 1u << 30, "copies.zip");
  ASSERT_EQ(all.entries().size(), 12u);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const ZipEntry* entry = all.find("creature-" + names[k] + ".ply");
    ASSERT_NE(entry, nullptr) << names[k];
    EXPECT_EQ(all.extract(*entry), owner().get("/v1/jobs/" + copies[k].value("job_id", "") + "/result").body)
        << "the copy as downloaded alone";
  }
  EXPECT_EQ(owner().get("/v1/models/" + model_ + "/copies.zip?recipient=nobody").status, 404);
  const std::size_t listed = owner().get("/v1/models/" + model_ + "/embeddings").json()["embeddings"].size();
  for (const nlohmann::json& bad :
       {nlohmann::json{{"recipients", {"x", "x"}}}, nlohmann::json{{"recipients", {}}},
        nlohmann::json{{"recipients", {"y"}}, {"recipient", "z"}}, nlohmann::json{{"recipients", {"y", 7}}}}) {
    const ApiResponse refused = owner().post_json("/v1/models/" + model_ + "/embed", bad);
    EXPECT_EQ(refused.status, 400) << bad.dump() << " " << refused.body;
  }
  std::vector<std::string> too_many(200, "");
  for (std::size_t k = 0; k < too_many.size(); ++k) too_many[k] = "many-" + std::to_string(k);
  const ApiResponse full = owner().post_json("/v1/models/" + model_ + "/embed", {{"recipients", too_many}});
  EXPECT_EQ(full.status, 503) << full.body << " (more than the owner's share of the queue)";
  EXPECT_EQ(owner().get("/v1/models/" + model_ + "/embeddings").json()["embeddings"].size(), listed)
      << "nothing of a refused batch is made";
}

// A suspect found in the wild, with no model named: among a hundred originals (the creature
// stretched a hundred ways), the search short-lists its original by shape and names the
// recipient; a shape the owner never uploaded is found in none.
TEST_F(DaemonBatch, ASuspectIsFoundAmongAHundredModelsWithoutItsId) {
  std::vector<std::string> ids;
  for (int wave = 0; wave < 100; wave += 16) {  // within the owner's share of the queue
    std::vector<std::string> jobs;
    for (int k = wave; k < std::min(100, wave + 16); ++k) {
      Mesh shape = creature(3);
      shape.V.col(0) *= 1.0 + 0.05 * (k % 10);
      shape.V.col(1) *= 1.0 + 0.05 * (k / 10);
      const ApiResponse r = owner().post_bytes("/v1/models?format=ply&name=shape-" + std::to_string(k),
                                               write_mesh_to_memory(shape, MeshFormat::ply, {.binary = true}));
      ASSERT_EQ(r.status, 202) << r.body;
      ids.push_back(r.json().at("id"));
      jobs.push_back(r.json().at("job_id"));
    }
    for (const std::string& job : jobs) ASSERT_EQ(owner().wait_job(job).value("state", ""), "succeeded");
  }
  const ApiResponse made = owner().post_json("/v1/models/" + ids[57] + "/embed", {{"recipient", "leaker"}});
  ASSERT_EQ(made.status, 202) << made.body;
  ASSERT_EQ(owner().wait_job(made.json().at("job_id")).value("state", ""), "succeeded");
  const Mesh copy = read_mesh_from_memory(owner().get("/v1/jobs/" + made.json().value("job_id", "") + "/result").body,
                                          MeshFormat::ply)
                        .mesh;
  const auto leaked = temp_dir("batch-search") / "found-in-the-wild.ply";
  write_mesh(leaked, transform_mesh(copy, random_similarity(copy, 11)), {.binary = true});

  const auto start = std::chrono::steady_clock::now();
  const CliRun found = run_cli("models detect " + leaked.string() + connection());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(found.exit_status, 0) << found.out;
  EXPECT_NE(found.out.find(": a copy of model \"shape-57\" (" + ids[57] + "): the copy given to \"leaker\""),
            std::string::npos)
      << found.out;
  EXPECT_NE(found.out.find("searched the 3 closest in shape of your "), std::string::npos) << found.out;
  const auto asked = std::chrono::steady_clock::now();
  const ApiResponse shortlist = owner().post_bytes("/v1/detect?format=ply&candidates=1", file_bytes(leaked.string()));
  const double ranking = std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
  ASSERT_EQ(shortlist.status, 202) << shortlist.body;
  EXPECT_EQ(shortlist.json()["candidates"][0].value("model_id", ""), ids[57]) << shortlist.body;
  EXPECT_EQ(shortlist.json().value("models_compared", 0), 101);
  std::printf(
      "[ figures  ] among %zu models: short-listed in %.3f s (the request); the CLI's whole search with "
      "3 detections %.2f s\n",
      ids.size() + 1, ranking, seconds);

  const auto stranger = temp_dir("batch-search") / "torus.ply";
  write_mesh(stranger, procedural_mesh("torus"), {.binary = true});
  const CliRun none = run_cli("models detect " + stranger.string() + connection());
  EXPECT_EQ(none.exit_status, 1) << none.out;
  EXPECT_NE(none.out.find(": no watermark of this key found in the 3 closest in shape"), std::string::npos) << none.out;
}

}  // namespace
}  // namespace meshmark::test
