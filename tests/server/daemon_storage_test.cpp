// The real daemon on a disk that fills up: uploads and embeds answer 507, no job is left
// 'running' or 'queued' without a worker, and everything finishes once space returns.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <thread>

#include "tests/server/api_client.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

using namespace std::chrono_literals;

// Fills the file system under `dir` with one file; returns its path.
std::filesystem::path fill(const std::filesystem::path& dir) {
  const auto filler = dir / "filler";
  std::ofstream out(filler, std::ios::binary);
  const std::string block(1 << 20, 'x');
  while (out.write(block.data(), static_cast<std::streamsize>(block.size()))) {
  }
  out.close();
  // Small writes may still fit in the last partial block: take it too.
  std::ofstream tail(dir / "filler-tail", std::ios::binary);
  while (tail.put('x')) {
  }
  return filler;
}

TEST(DaemonStorage, AFullDiskAnswers507LeavesNoJobStuckAndRecoversWhenSpaceReturns) {
  if (std::system("unshare -m true 2>/dev/null") != 0) GTEST_SKIP() << "cannot make a mount namespace here";
  const auto data = temp_dir("full-disk");
  // The data folder on a 48 MB tmpfs of its own, in the daemon's own mount namespace.
  DaemonProcess daemon(
      data, {"--workers", "1"},
      {"unshare", "-m", "sh", "-c", "mount -t tmpfs -o size=48m meshmark-test \"$1\" && shift && exec \"$@\"", "sh",
       data.string()});
  const auto inside = std::filesystem::path("/proc") / std::to_string(daemon.pid()) / "root" / data.relative_path();
  ASSERT_TRUE(std::filesystem::exists(inside / "meshmark.db")) << inside;

  const std::string key = ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "full");
  const ApiClient owner(daemon.port(), key);
  const std::string creature = file_bytes(procedural_file("creature"));
  const std::string model = owner.upload_ready(creature, "obj", "creature").at("id").get<std::string>();

  const auto filler = fill(inside);
  std::filesystem::remove(inside / "filler-tail");
  // Leave room for a few database pages but not for a mesh: the database takes the embed, the
  // blob store then refuses the watermarked copy.
  std::filesystem::resize_file(filler, std::filesystem::file_size(filler) - (128 << 10));
  const ApiResponse upload = owner.post_bytes("/v1/models?format=obj", creature);
  EXPECT_EQ(upload.status, 507) << upload.body;
  EXPECT_TRUE(upload.is_problem());
  EXPECT_EQ(upload.body.find(data.string()), std::string::npos) << "a server path in: " << upload.body;
  const ApiResponse embed = owner.post_json("/v1/models/" + model + "/embed", {{"recipient", "while-full"}});
  ASSERT_EQ(embed.status, 202) << embed.body;
  const std::string job = embed.json().at("job_id").get<std::string>();
  // The job is owned by the queue while it waits for storage, and readiness says so.
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  ApiResponse ready = owner.get("/readyz");
  while (ready.json().value("waiting_for_storage", 0) == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(100ms);
    ready = owner.get("/readyz");
  }
  EXPECT_EQ(ready.status, 503) << ready.body;
  EXPECT_EQ(ready.json().value("waiting_for_storage", 0), 1) << ready.body;
  EXPECT_TRUE(ready.is_problem()) << "not ready, and never says \"ready\": " << ready.body;
  EXPECT_EQ(ready.json().value("status", 0), 503) << ready.body;
  // Meanwhile more work is refused with 507, never 500.
  const ApiResponse more = owner.post_json("/v1/models/" + model + "/embed", {{"recipient", "refused"}});
  EXPECT_TRUE(more.status == 507 || more.status == 202) << more.status << " " << more.body;
  std::vector<std::string> jobs = {job};
  if (more.status == 202) jobs.push_back(more.json().at("job_id").get<std::string>());

  std::filesystem::remove(filler);
  for (const std::string& job : jobs) EXPECT_EQ(owner.wait_job(job, 90).value("state", ""), "succeeded") << job;
  const ApiResponse again = owner.post_json("/v1/models/" + model + "/embed", {{"recipient", "after"}});
  ASSERT_EQ(again.status, 202) << again.body;
  EXPECT_EQ(owner.wait_job(again.json().at("job_id").get<std::string>()).value("state", ""), "succeeded");
  EXPECT_EQ(owner.post_bytes("/v1/models?format=obj", creature).status, 202);
  EXPECT_EQ(owner.get("/readyz").status, 200);
}

// Meshes, preparations and copies in the S3-compatible server the test command starts: nothing of
// them on the daemon's disk, and a restarted daemon serves the same copy and traces it.
TEST(DaemonObjectStore, MeshesLiveInAnObjectStoreAndOutliveTheDaemon) {
  const char* endpoint = std::getenv("MESHMARK_TEST_S3_ENDPOINT");
  if (!endpoint) GTEST_SKIP() << "no S3-compatible server (MESHMARK_TEST_S3_ENDPOINT)";
  ::setenv("MESHMARK_S3_ENDPOINT", endpoint, 1);
  ::setenv("AWS_ACCESS_KEY_ID", "S3RVER", 1);
  ::setenv("AWS_SECRET_ACCESS_KEY", "S3RVER", 1);
  const auto data = temp_dir("s3-daemon");
  const std::vector<std::string> flags = {"--blobs", "s3://meshmark-test/" + data.filename().string()};
  std::string copy, job_id, key, model_id;
  {
    DaemonProcess daemon(data, flags);
    key = ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "studio");
    const ApiClient owner(daemon.port(), key);
    model_id = owner.upload_ready(file_bytes(procedural_file("creature")), "obj", "creature").at("id");
    const ApiResponse accepted = owner.post_json("/v1/models/" + model_id + "/embed", {{"recipient", "shop-s3"}});
    ASSERT_EQ(accepted.status, 202) << accepted.body;
    job_id = accepted.json().at("job_id");
    ASSERT_EQ(owner.wait_job(job_id).value("state", ""), "succeeded");
    const ApiResponse download = owner.get("/v1/jobs/" + job_id + "/result");
    ASSERT_EQ(download.status, 200);
    copy = download.body;
    EXPECT_FALSE(std::filesystem::exists(data / "blobs")) << "no mesh on the daemon's disk";
  }
  DaemonProcess again(data, flags);
  const ApiClient owner(again.port(), key);
  EXPECT_EQ(owner.get("/v1/jobs/" + job_id + "/result").body, copy) << "byte-identical after a restart";
  const ApiResponse detect = owner.post_bytes("/v1/models/" + model_id + "/detect?format=obj", copy);
  ASSERT_EQ(detect.status, 202) << detect.body;
  const nlohmann::json traced = owner.wait_job(detect.json().at("job_id"));
  EXPECT_EQ(traced["result"]["match"].value("recipient", ""), "shop-s3") << traced.dump();
}

}  // namespace
}  // namespace meshmark::test
