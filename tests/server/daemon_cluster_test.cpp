// Three daemons on one PostgreSQL store and one S3-compatible bucket (the servers the test
// command starts): what one accepts, any other serves and traces; a daemon killed mid-job loses
// no job — another takes it over once its lease ran out.

#include <gtest/gtest.h>
#include <libpq-fe.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <thread>

#include "core/io/write_mesh.hpp"
#include "core/mesh/example_shapes.hpp"
#include "tests/build_paths.hpp"
#include "tests/server/api_client.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/server/storage_backends.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

using namespace std::chrono_literals;

class DaemonCluster : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::getenv("MESHMARK_TEST_POSTGRES") || !std::getenv("MESHMARK_TEST_S3_ENDPOINT"))
      GTEST_SKIP() << "no PostgreSQL or S3-compatible server (MESHMARK_TEST_POSTGRES, MESHMARK_TEST_S3_ENDPOINT)";
    ::setenv("MESHMARK_S3_ENDPOINT", std::getenv("MESHMARK_TEST_S3_ENDPOINT"), 1);
    ::setenv("AWS_ACCESS_KEY_ID", "S3RVER", 1);
    ::setenv("AWS_SECRET_ACCESS_KEY", "S3RVER", 1);
    const auto key = shared / "master.key";
    std::ofstream(key) << "cluster-master-key-0123456789abcdef0123456789abcdef\n";
    std::filesystem::permissions(key, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
    start_cluster(postgres_test_database(shared));
  }
  // Three daemons on the store at `store_uri` (replacing any running), and an owner.
  void start_cluster(const std::string& store_uri) {
    for (auto& d : daemons) d.reset();
    flags = {"--store",           store_uri,
             "--blobs",           "s3://meshmark-test/" + shared.filename().string(),
             "--master-key-file", (shared / "master.key").string(),
             "--lease-seconds",   "3",
             "--threads-per-job", "1",
             "--workers",         "1"};
    for (int i = 0; i < 3; ++i) start(i);
    key_ = ApiClient(daemons[0]->port(), "").create_owner(DaemonProcess::admin_token(), "studio");
  }
  void start(int i) { daemons[i] = std::make_unique<DaemonProcess>(temp_dir("node"), flags); }
  ApiClient owner(int i) const { return ApiClient(daemons[i]->port(), key_); }
  // Polls through daemon `i` until the job leaves queued/running (through a 503 or two while a
  // daemon reconnects to its store).
  nlohmann::json finished(int i, const std::string& job_id) const {
    for (int attempt = 0;; ++attempt) {
      try {
        return owner(i).wait_job(job_id, 120);
      } catch (const std::runtime_error&) {
        if (attempt == 20) throw;
        std::this_thread::sleep_for(250ms);
      }
    }
  }
  // Polls until the job runs (or has ended).
  void wait_running(int i, const std::string& job_id) const {
    for (int k = 0; k < 2000; ++k, std::this_thread::sleep_for(5ms))
      if (owner(i).get("/v1/jobs/" + job_id).json().value("state", "") != "queued") return;
  }

  std::filesystem::path shared = temp_dir("cluster");
  std::vector<std::string> flags;
  std::unique_ptr<DaemonProcess> daemons[3];
  std::string key_;
};

TEST_F(DaemonCluster, ACopyMadeThroughOneDaemonIsServedAndTracedThroughTheOthers) {
  const std::string model = owner(1).upload_ready(file_bytes(procedural_file("creature")), "obj", "creature").at("id");
  const ApiResponse accepted = owner(2).post_json("/v1/models/" + model + "/embed", {{"recipient", "partner-x"}});
  ASSERT_EQ(accepted.status, 202) << accepted.body;
  const std::string job = accepted.json().at("job_id");
  ASSERT_EQ(finished(0, job).value("state", ""), "succeeded");
  const std::string copy = owner(0).get("/v1/jobs/" + job + "/result").body;
  EXPECT_EQ(owner(1).get("/v1/jobs/" + job + "/result").body, copy) << "the same bytes from every daemon";
  const ApiResponse detect = owner(0).post_bytes("/v1/models/" + model + "/detect?format=obj", copy);
  ASSERT_EQ(detect.status, 202) << detect.body;
  const nlohmann::json traced = finished(1, detect.json().at("job_id"));
  EXPECT_EQ(traced["result"]["match"].value("recipient", ""), "partner-x") << traced.dump();
  // Owners are the store's: another owner, made on another daemon, finds nothing of this one.
  const std::string other_key = ApiClient(daemons[2]->port(), "").create_owner(DaemonProcess::admin_token(), "other");
  EXPECT_EQ(ApiClient(daemons[0]->port(), other_key).get("/v1/models/" + model).status, 404);
  EXPECT_EQ(ApiClient(daemons[1]->port(), other_key).get("/v1/jobs/" + job).status, 404);
}

// A copy asked of one daemon while another prepares its model waits for the preparation.
TEST_F(DaemonCluster, ACopyAskedWhileAnotherDaemonPreparesItsModelWaitsForIt) {
  const ApiResponse upload =
      owner(0).post_bytes("/v1/models?format=obj&name=creature", file_bytes(procedural_file("creature_large")));
  ASSERT_EQ(upload.status, 202) << upload.body;
  const std::string model = upload.json().at("id");
  const ApiResponse embed = owner(1).post_json("/v1/models/" + model + "/embed", {{"recipient", "early"}});
  ASSERT_EQ(embed.status, 202) << embed.body;
  const nlohmann::json made = finished(1, embed.json().at("job_id"));
  EXPECT_EQ(made.value("state", ""), "succeeded") << made.dump();
  EXPECT_EQ(made.value("attempts", 0), 1) << "waiting is not an attempt";
}

// Daemon 0's one worker is busy preparing; a copy queued behind it there is claimed by an idle
// daemon and made before the preparation ends.
TEST_F(DaemonCluster, AnIdleDaemonRunsWhatWaitsBehindABusyOne) {
  const std::string ready = owner(1).upload_ready(file_bytes(procedural_file("creature")), "obj", "creature").at("id");
  const std::string large = write_mesh_to_memory(creature(6), MeshFormat::ply, {.binary = true});  // 41k vertices
  const ApiResponse upload = owner(0).post_bytes("/v1/models?format=ply&name=large", large);
  ASSERT_EQ(upload.status, 202) << upload.body;
  wait_running(0, upload.json().at("job_id"));
  const ApiResponse embed = owner(0).post_json("/v1/models/" + ready + "/embed", {{"recipient", "waiting"}});
  ASSERT_EQ(embed.status, 202) << embed.body;
  const nlohmann::json made = finished(1, embed.json().at("job_id"));
  const nlohmann::json prepared = finished(1, upload.json().at("job_id"));
  EXPECT_EQ(made.value("state", ""), "succeeded") << made.dump();
  EXPECT_LT(made.value("finished_at", ""), prepared.value("finished_at", "")) << prepared.dump();
}

// Thirty jobs — fifteen copies and fifteen detections — asked round robin of the three daemons:
// every one ends succeeded, each detection names its copy's recipient, every copy downloads the
// same from each daemon, and nothing is left queued or running.
TEST_F(DaemonCluster, ThirtyJobsSpreadOverTheDaemonsAllEndAndAgree) {
  const std::string model = owner(0).upload_ready(file_bytes(procedural_file("creature")), "obj", "creature").at("id");
  std::vector<std::string> embeds;
  for (int k = 0; k < 15; ++k) {
    const ApiResponse r =
        owner(k % 3).post_json("/v1/models/" + model + "/embed", {{"recipient", "partner-" + std::to_string(k)}});
    ASSERT_EQ(r.status, 202) << r.body;
    embeds.push_back(r.json().at("job_id"));
  }
  std::vector<std::pair<std::string, std::string>> detections;  // job, the recipient it should name
  for (int k = 0; k < 15; ++k) {
    ASSERT_EQ(finished(k % 3, embeds[k]).value("state", ""), "succeeded");
    const std::string copy = owner(k % 3).get("/v1/jobs/" + embeds[k] + "/result").body;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(owner(i).get("/v1/jobs/" + embeds[k] + "/result").body, copy);
    const ApiResponse d = owner((k + 1) % 3).post_bytes("/v1/models/" + model + "/detect?format=obj", copy);
    ASSERT_EQ(d.status, 202) << d.body;
    detections.emplace_back(d.json().at("job_id"), "partner-" + std::to_string(k));
  }
  for (const auto& [job, recipient] : detections) {
    const nlohmann::json traced = finished(2, job);
    EXPECT_EQ(traced["result"]["match"].value("recipient", ""), recipient) << traced.dump();
  }
  const std::string metrics = ApiClient(daemons[0]->port(), "").get("/metrics").body;
  EXPECT_NE(metrics.find("meshmark_jobs{kind=\"embed\",state=\"succeeded\"} 15"), std::string::npos) << metrics;
  EXPECT_EQ(metrics.find("state=\"running\"}"), std::string::npos) << "none left running: " << metrics;
  EXPECT_EQ(metrics.find("state=\"queued\"}"), std::string::npos) << "none left queued: " << metrics;
  EXPECT_EQ(owner(1).get("/v1/models/" + model + "/embeddings").json()["embeddings"].size(), 15u);
}

// kill -9 while a preparation runs, then while an embed is queued or running: each job ends on
// another daemon, its attempt counted, and nothing is left running.
TEST_F(DaemonCluster, AJobOfADaemonKilledMidwayFinishesOnAnother) {
  const ApiResponse upload =
      owner(0).post_bytes("/v1/models?format=obj&name=creature", file_bytes(procedural_file("creature_large")));
  ASSERT_EQ(upload.status, 202) << upload.body;
  const std::string model = upload.json().at("id"), prepare = upload.json().at("job_id");
  wait_running(1, prepare);
  daemons[0]->kill_hard();
  const nlohmann::json prepared = finished(1, prepare);
  EXPECT_EQ(prepared.value("state", ""), "succeeded") << prepared.dump();
  EXPECT_EQ(prepared.value("attempts", 0), 2) << "run again after its daemon died";

  const ApiResponse embed = owner(1).post_json("/v1/models/" + model + "/embed", {{"recipient", "partner-y"}});
  ASSERT_EQ(embed.status, 202) << embed.body;
  daemons[1]->kill_hard();
  const nlohmann::json made = finished(2, embed.json().at("job_id"));
  ASSERT_EQ(made.value("state", ""), "succeeded") << made.dump();
  const std::string copy = owner(2).get("/v1/jobs/" + made.value("id", "") + "/result").body;
  const ApiResponse detect = owner(2).post_bytes("/v1/models/" + model + "/detect?format=obj", copy);
  EXPECT_EQ(finished(2, detect.json().at("job_id"))["result"]["match"].value("recipient", ""), "partner-y");
}

// Every daemon's connections cut by the database (pg_terminate_backend, as a failover or an
// operator would): requests answer 503 with Retry-After until the pool has reconnected, never a
// wrong answer, and a job accepted before the cut still ends.
TEST_F(DaemonCluster, ConnectionsCutByTheDatabaseAreReopened) {
  const std::string model = owner(0).upload_ready(file_bytes(procedural_file("creature")), "obj", "creature").at("id");
  const ApiResponse embed = owner(1).post_json("/v1/models/" + model + "/embed", {{"recipient", "partner-z"}});
  ASSERT_EQ(embed.status, 202) << embed.body;
  PGconn* admin = PQconnectdb(postgres_test_database(shared).c_str());
  PQclear(PQexec(admin,
                 "SELECT pg_terminate_backend(pid) FROM pg_stat_activity "
                 "WHERE datname = current_database() AND pid <> pg_backend_pid()"));
  PQfinish(admin);
  for (int i = 0; i < 3; ++i) {
    int status = 0;
    for (int attempt = 0; attempt < 20 && status != 200; ++attempt) {
      const ApiResponse r = owner(i).get("/v1/models/" + model);
      status = r.status;
      if (status != 200) {
        EXPECT_EQ(status, 503) << r.body;
        EXPECT_FALSE(r.header("Retry-After").empty());
      }
    }
    EXPECT_EQ(status, 200) << "daemon " << i << " reconnected";
  }
  EXPECT_EQ(finished(2, embed.json().at("job_id")).value("state", ""), "succeeded");
}

// PostgreSQL restarted while copies are being made: every job accepted before ends succeeded
// (a store that does not answer makes a job wait and run again), none is left running.
// (On a PostgreSQL of its own: restarting the shared test server would cut the other tests.)
TEST_F(DaemonCluster, ADatabaseRestartedUnderLoadLosesNothingAcknowledged) {
  const std::string script = std::string(test::source_dir()) + "/deploy/postgres-test-server.sh ";
  const auto folder = temp_dir("private-postgres");
  FILE* started = ::popen((script + (folder / "pg").string()).c_str(), "r");
  char uri[256] = {};
  const bool read = std::fgets(uri, sizeof uri, started) != nullptr;
  ASSERT_EQ(::pclose(started), 0);
  ASSERT_TRUE(read);
  struct Stop {
    std::string command;
    ~Stop() { std::system(command.c_str()); }
  } stop{script + (folder / "pg").string() + " stop"};
  start_cluster(std::string(uri, std::strcspn(uri, "\n")));
  const std::string restart = script + (folder / "pg").string() + " restart";
  const std::string model = owner(0).upload_ready(file_bytes(procedural_file("creature")), "obj", "creature").at("id");
  std::vector<std::string> jobs;
  for (int k = 0; k < 6; ++k) {
    const ApiResponse r =
        owner(k % 3).post_json("/v1/models/" + model + "/embed", {{"recipient", "r" + std::to_string(k)}});
    ASSERT_EQ(r.status, 202) << r.body;
    jobs.push_back(r.json().at("job_id"));
  }
  ASSERT_EQ(std::system(restart.c_str()), 0);
  for (const std::string& job : jobs) {
    nlohmann::json view;
    for (int attempt = 0; attempt < 60 && !view.is_object(); ++attempt) {
      const ApiResponse r = owner(0).get("/v1/jobs/" + job);
      if (r.status == 200) view = finished(0, job);
      else std::this_thread::sleep_for(500ms);  // 503 while the pool reconnects
    }
    EXPECT_EQ(view.value("state", ""), "succeeded") << view.dump();
  }
  EXPECT_EQ(owner(1).get("/v1/models/" + model + "/embeddings").json()["embeddings"].size(), jobs.size());
}

// SIGTERM on one daemon: it finishes what it runs while the others keep serving.
TEST_F(DaemonCluster, ADaemonDrainingLeavesTheOthersServing) {
  const ApiResponse upload =
      owner(0).post_bytes("/v1/models?format=obj&name=creature", file_bytes(procedural_file("creature_large")));
  ASSERT_EQ(upload.status, 202) << upload.body;
  wait_running(0, upload.json().at("job_id"));
  daemons[0]->send_term();
  EXPECT_EQ(owner(1).get("/v1/models/" + upload.json().value("id", "")).status, 200);
  EXPECT_EQ(owner(2).get("/readyz").status, 200);
  EXPECT_EQ(daemons[0]->wait_exit(), 0);
  EXPECT_EQ(finished(1, upload.json().at("job_id")).value("state", ""), "succeeded") << "finished while draining";
}

}  // namespace
}  // namespace meshmark::test
