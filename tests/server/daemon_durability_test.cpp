// The real daemon stopped cleanly, and killed in the middle of work: nothing acknowledged is lost.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "tests/server/api_client.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

void wait_for_state(const ApiClient& client, const std::string& job_path, const std::string& state) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (client.get(job_path).json().value("state", "") != state) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << job_path << " never reached " << state;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

TEST(DaemonDurability, ARestartKeepsOwnersModelsEmbeddingsAndFinishedJobs) {
  const auto data = temp_dir("restart");
  std::string key, model_path, job_id, marked;
  {
    DaemonProcess daemon(data);
    key = ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "r");
    const ApiClient owner(daemon.port(), key);
    model_path =
        "/v1/models/" +
        owner.upload_ready(file_bytes(procedural_file("creature")), "obj", "creature").at("id").get<std::string>();
    const ApiResponse embed = owner.post_json(model_path + "/embed", {{"recipient", "kept"}});
    job_id = embed.json().at("job_id").get<std::string>();
    ASSERT_EQ(owner.wait_job(job_id).value("state", ""), "succeeded");
    marked = owner.get("/v1/jobs/" + job_id + "/result").body;
    EXPECT_EQ(daemon.terminate(), 0);
  }
  DaemonProcess daemon(data);
  const ApiClient owner(daemon.port(), key);
  EXPECT_EQ(owner.get(model_path).json().value("state", ""), "ready");
  EXPECT_EQ(owner.get("/v1/jobs/" + job_id).json().value("state", ""), "succeeded");
  EXPECT_EQ(owner.get("/v1/jobs/" + job_id + "/result").body, marked);
  const auto embeddings = owner.get(model_path + "/embeddings").json()["embeddings"];
  ASSERT_EQ(embeddings.size(), 1u);
  EXPECT_EQ(embeddings[0].value("recipient", ""), "kept");
  // The prepared model came back from the store, with the same keys: the copy is still traced.
  const ApiResponse detect = owner.post_bytes(model_path + "/detect?format=obj", marked);
  const auto result = owner.wait_job(detect.json().at("job_id").get<std::string>())["result"];
  ASSERT_TRUE(result["match"].is_object()) << result.dump();
  EXPECT_EQ(result["match"].value("recipient", ""), "kept");
}

// The data folder is the daemon user's alone, and a start removes what a killed run left
// half-written.
TEST(DaemonDurability, TheDataFolderIsPrivateAndHalfWrittenFilesAreSweptAtStart) {
  namespace fs = std::filesystem;
  const auto data = temp_dir("private");
  {
    DaemonProcess first(data);
    ApiClient anonymous(first.port(), "");
    anonymous.create_owner(DaemonProcess::admin_token(), "studio");
  }
  fs::create_directories(data / "blobs" / "jobs");
  std::ofstream(data / "blobs" / "jobs" / ".tmp-output.ply-123-0") << "half";
  fs::permissions(data / "meshmark.db", fs::perms::others_read | fs::perms::group_read, fs::perm_options::add);
  DaemonProcess second(data);
  EXPECT_FALSE(fs::exists(data / "blobs" / "jobs" / ".tmp-output.ply-123-0"));
  EXPECT_EQ(fs::status(data).permissions() & fs::perms::all, fs::perms::owner_all);
  for (const char* file : {"meshmark.db", "master.key"})
    EXPECT_EQ(fs::status(data / file).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write)
        << file;
}

TEST(DaemonDurability, KillDashNineMidWorkLosesNothingAndTheInterruptedJobsRunAgain) {
  const auto data = temp_dir("kill9");
  std::string key, model_path, prepare_job, embed_job;
  {
    DaemonProcess daemon(data, {"--workers", "1"});
    key = ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "k");
    const ApiClient owner(daemon.port(), key);
    const ApiResponse upload = owner.post_bytes("/v1/models?format=obj", file_bytes(procedural_file("creature_large")));
    ASSERT_EQ(upload.status, 202);
    model_path = "/v1/models/" + upload.json().at("id").get<std::string>();
    prepare_job = "/v1/jobs/" + upload.json().at("job_id").get<std::string>();
    const ApiResponse embed = owner.post_json(model_path + "/embed", {{"payload", "c0ffee"}, {"recipient", "k9"}});
    ASSERT_EQ(embed.status, 202);
    embed_job = "/v1/jobs/" + embed.json().at("job_id").get<std::string>();
    wait_for_state(owner, prepare_job, "running");
    daemon.kill_hard();  // mid-parameterization
  }
  DaemonProcess daemon(data, {"--workers", "1"});
  const ApiClient owner(daemon.port(), key);
  const auto prepared = owner.wait_job(prepare_job.substr(std::string("/v1/jobs/").size()));
  EXPECT_EQ(prepared.value("state", ""), "succeeded") << prepared.dump();
  const auto embedded = owner.wait_job(embed_job.substr(std::string("/v1/jobs/").size()));
  EXPECT_EQ(embedded.value("state", ""), "succeeded") << embedded.dump();
  EXPECT_EQ(embedded["result"].value("payload", ""), "c0ffee");
  EXPECT_EQ(owner.get(model_path).json().value("state", ""), "ready");
  EXPECT_EQ(owner.get(model_path + "/embeddings").json()["embeddings"].size(), 1u);
}

TEST(DaemonDurability, SigtermRefusesNewWorkLetsTheRunningJobFinishAndExitsZero) {
  const auto data = temp_dir("sigterm");
  std::string key, prepare_job;
  {
    // The grace period is what the test is about, not its length: a loaded CI machine may take
    // more than the default 60 s to parameterize the mesh.
    DaemonProcess daemon(data, {"--workers", "1", "--shutdown-grace", "600"});
    key = ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "t");
    const ApiClient owner(daemon.port(), key);
    const ApiResponse upload = owner.post_bytes("/v1/models?format=obj", file_bytes(procedural_file("creature_large")));
    ASSERT_EQ(upload.status, 202);
    prepare_job = upload.json().at("job_id").get<std::string>();
    wait_for_state(owner, "/v1/jobs/" + prepare_job, "running");
    daemon.send_term();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const ApiResponse refused = owner.post_bytes("/v1/models?format=obj", file_bytes(procedural_file("creature")));
    EXPECT_EQ(refused.status, 503) << refused.body;
    EXPECT_EQ(owner.get("/readyz").status, 503);
    EXPECT_EQ(daemon.wait_exit(), 0);
  }
  DaemonProcess daemon(data, {"--workers", "1"});
  const auto job = ApiClient(daemon.port(), key).get("/v1/jobs/" + prepare_job).json();
  EXPECT_EQ(job.value("state", ""), "succeeded") << job.dump();
  EXPECT_EQ(job.value("attempts", 0), 1);  // finished during the drain, not run again
}

}  // namespace
}  // namespace meshmark::test
