// The real daemon under load: a full queue, cancellation, and many embed jobs at once.

#include <gtest/gtest.h>

#include <future>
#include <thread>

#include "tests/server/api_client.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

// Uploads the large creature and returns its path once a worker has started preparing it.
std::string model_being_prepared(const ApiClient& owner) {
  const ApiResponse upload =
      owner.post_bytes("/v1/models?format=obj&name=creature", file_bytes(procedural_file("creature_large")));
  if (upload.status != 202) throw std::runtime_error("upload refused: " + upload.body);
  const std::string prepare_job = "/v1/jobs/" + upload.json().at("job_id").get<std::string>();
  while (owner.get(prepare_job).json().value("state", "") == "queued")
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return "/v1/models/" + upload.json().at("id").get<std::string>();
}

TEST(DaemonQueue, AFullQueueAnswers503WithRetryAfterAndACanceledJobFreesItsPlace) {
  DaemonProcess daemon(temp_dir("queue"), {"--workers", "1", "--max-queue", "1"});
  const ApiClient owner(daemon.port(), ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "q"));
  // The single worker busy preparing: the queue is then empty, with one place.
  const std::string model = model_being_prepared(owner);

  const ApiResponse first = owner.post_json(model + "/embed", {{"payload", "01"}});
  ASSERT_EQ(first.status, 202) << first.body;
  const ApiResponse second = owner.post_json(model + "/embed", {{"payload", "02"}});
  EXPECT_EQ(second.status, 503) << second.body;
  EXPECT_TRUE(second.is_problem());
  EXPECT_FALSE(second.header("Retry-After").empty());

  const std::string first_job = "/v1/jobs/" + first.json().at("job_id").get<std::string>();
  const ApiResponse cancel = owner.del(first_job);
  EXPECT_EQ(cancel.status, 200) << cancel.body;
  EXPECT_EQ(owner.get(first_job).json().value("state", ""), "canceled");

  const ApiResponse third = owner.post_json(model + "/embed", {{"payload", "03"}});
  ASSERT_EQ(third.status, 202) << third.body;
  const auto done = owner.wait_job(third.json().at("job_id").get<std::string>());
  EXPECT_EQ(done.value("state", ""), "succeeded") << done.dump();
  EXPECT_EQ(owner.get(first_job).json().value("state", ""), "canceled");  // never ran
  EXPECT_EQ(owner.get(first_job + "/result").status, 409);
}

// Four places, half for one owner: while the single worker prepares, owner "q" queues two embeds
// and the third is refused naming its share; another owner's upload still finds a place.
TEST(DaemonQueue, OneOwnerHoldsAtMostItsShareOfTheQueue) {
  DaemonProcess daemon(temp_dir("share"), {"--workers", "1", "--max-queue", "4", "--owner-queue-share", "0.5"});
  const ApiClient admin(daemon.port(), "");
  const ApiClient owner(daemon.port(), admin.create_owner(DaemonProcess::admin_token(), "q"));
  const ApiClient other(daemon.port(), admin.create_owner(DaemonProcess::admin_token(), "r"));
  const std::string model = model_being_prepared(owner);

  for (const char* payload : {"01", "02"})
    ASSERT_EQ(owner.post_json(model + "/embed", {{"payload", payload}}).status, 202);
  const ApiResponse third = owner.post_json(model + "/embed", {{"payload", "03"}});
  EXPECT_EQ(third.status, 503) << third.body;
  EXPECT_NE(third.body.find("your share of the job queue"), std::string::npos) << third.body;
  EXPECT_FALSE(third.header("Retry-After").empty());
  const ApiResponse elsewhere =
      other.post_bytes("/v1/models?format=obj&name=c", file_bytes(procedural_file("creature")));
  EXPECT_EQ(elsewhere.status, 202) << elsewhere.body;
}

// A model still preparing names its preparation job and how far it is; a ready one does not.
TEST(DaemonQueue, APreparingModelShowsItsPreparationsProgress) {
  DaemonProcess daemon(temp_dir("preparation"), {"--workers", "1"});
  const ApiClient owner(daemon.port(), ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "p"));
  const std::string running = model_being_prepared(owner);
  const ApiResponse upload =
      owner.post_bytes("/v1/models?format=obj&name=queued", file_bytes(procedural_file("creature")));
  ASSERT_EQ(upload.status, 202) << upload.body;
  EXPECT_EQ(upload.json()["preparation"].value("job_id", ""), upload.json().value("job_id", "?"));

  const nlohmann::json queued = owner.get("/v1/models/" + upload.json().at("id").get<std::string>()).json();
  EXPECT_EQ(queued["preparation"].value("state", ""), "queued") << queued.dump();
  EXPECT_EQ(queued["preparation"].value("progress", -1.0), 0.0);
  EXPECT_EQ(queued["links"].value("preparation", ""), "/v1/jobs/" + upload.json().value("job_id", "?"));
  const nlohmann::json listed = owner.get("/v1/models").json()["models"];
  ASSERT_EQ(listed.size(), 2u);
  for (const nlohmann::json& m : listed)
    EXPECT_EQ(m.contains("preparation"), m.value("state", "") == "preparing") << m.dump();
  const nlohmann::json first = owner.get(running).json();
  if (first.value("state", "") == "preparing") {  // unless it finished meanwhile
    EXPECT_EQ(first["preparation"].value("state", ""), "running") << first.dump();
  }

  owner.wait_job(upload.json().at("job_id").get<std::string>());
  const nlohmann::json ready = owner.get("/v1/models/" + upload.json().at("id").get<std::string>()).json();
  EXPECT_EQ(ready.value("state", ""), "ready");
  EXPECT_FALSE(ready.contains("preparation")) << ready.dump();
  EXPECT_FALSE(ready["links"].contains("preparation"));
}

TEST(DaemonConcurrency, TwelveConcurrentEmbedsAllSucceedWithTheirOwnPayloads) {
  DaemonProcess daemon(temp_dir("concurrency"));
  const ApiClient owner(daemon.port(), ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "c"));
  const auto model = owner.upload_ready(file_bytes(procedural_file("creature", "off")), "off", "creature");
  const std::string path = "/v1/models/" + model.at("id").get<std::string>();

  constexpr int kJobs = 12;  // six times the workers: jobs queue, run side by side and finish out of order
  auto payload_of = [](int i) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", 0x9e3779b97f4a7c15ull * static_cast<unsigned long long>(i + 1));
    return std::string(hex);
  };
  std::vector<std::future<ApiResponse>> posts;
  for (int i = 0; i < kJobs; ++i)
    posts.push_back(std::async(std::launch::async, [&, i] {
      return owner.post_json(path + "/embed", {{"payload", payload_of(i)}, {"recipient", "r" + std::to_string(i)}});
    }));
  std::vector<std::string> jobs;
  for (auto& p : posts) {
    const ApiResponse r = p.get();
    ASSERT_EQ(r.status, 202) << r.body;
    jobs.push_back(r.json().at("job_id").get<std::string>());
  }

  // Each finished copy carries its own payload: detect every one (also concurrently).
  std::vector<std::future<nlohmann::json>> detections;
  for (int i = 0; i < kJobs; ++i)
    detections.push_back(std::async(std::launch::async, [&, i] {
      const auto job = owner.wait_job(jobs[static_cast<std::size_t>(i)]);
      if (job.value("state", "") != "succeeded") return job;
      const ApiResponse copy = owner.get("/v1/jobs/" + jobs[static_cast<std::size_t>(i)] + "/result");
      const ApiResponse posted = owner.post_bytes(path + "/detect?format=off", copy.body);
      return owner.wait_job(posted.json().at("job_id").get<std::string>());
    }));
  for (int i = 0; i < kJobs; ++i) {
    const auto detection = detections[static_cast<std::size_t>(i)].get();
    ASSERT_EQ(detection.value("state", ""), "succeeded") << detection.dump();
    const auto& result = detection["result"];
    EXPECT_EQ(result.value("decoded", ""), payload_of(i));
    ASSERT_TRUE(result["match"].is_object());
    EXPECT_EQ(result["match"].value("recipient", ""), "r" + std::to_string(i));
  }
  EXPECT_EQ(owner.get(path + "/embeddings").json()["embeddings"].size(), static_cast<std::size_t>(kJobs));
}

}  // namespace
}  // namespace meshmark::test
