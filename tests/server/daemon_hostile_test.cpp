// The real daemon against hostile clients, on raw sockets: no single request may crash it, hang
// it or desynchronize a connection; slow and idle connections may not starve it.

#include <gtest/gtest.h>

#include <fstream>

#include <memory>
#include <thread>

#include "core/io/write_mesh.hpp"
#include "tests/server/api_client.hpp"
#include "server/daemon_secrets.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

using namespace std::chrono_literals;

class DaemonHostile : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon_ = new DaemonProcess(temp_dir("hostile"));
    const OwnerWithModel made = owner_with_creature(daemon_->port(), "red-team");
    key_ = made.key;
    model_ = made.model;
  }
  static void TearDownTestSuite() {
    delete daemon_;
    daemon_ = nullptr;
  }

  static int port() { return daemon_->port(); }
  static std::string auth() { return "Authorization: Bearer " + key_ + "\r\n"; }
  static ApiClient owner() { return ApiClient(port(), key_); }

  // The daemon still answers, on a fresh connection.
  static void expect_alive() {
    const ApiResponse r = owner().get("/livez");
    EXPECT_EQ(r.status, 200) << "the daemon no longer answers";
  }

  // Sends `request` with a smuggled second request as its body: the first must be answered and
  // the connection closed, the smuggled one never answered.
  static std::string refused_with_smuggled_body(const std::string& head) {
    const std::string smuggled = "GET /metrics HTTP/1.1\r\nHost: x\r\n\r\n";
    RawConnection c(port());
    c.send(head + smuggled);
    const std::string first = c.read_response();
    EXPECT_TRUE(c.closed_within(3s)) << "the connection stayed open after a refusal: " << first;
    EXPECT_EQ(first.find("Keep-Alive"), std::string::npos) << first;
    EXPECT_NE(first.find("Connection: close"), std::string::npos) << first;
    return first;
  }

  static DaemonProcess* daemon_;
  static std::string key_;
  static std::string model_;
};

DaemonProcess* DaemonHostile::daemon_ = nullptr;
std::string DaemonHostile::key_;
std::string DaemonHostile::model_;

TEST_F(DaemonHostile, PathsThatAreNotUtf8Get404AndTheDaemonLives) {
  for (const std::string path : {"/%FF", "/v1/models/%FF", "/v1/jobs/%C3%28", "/\xFF"}) {
    RawConnection c(port());
    c.send("GET " + path + " HTTP/1.1\r\nHost: x\r\n" + auth() + "\r\n");
    const std::string response = c.read_response();
    EXPECT_EQ(status_of(response), 404) << path << ": " << response;
    EXPECT_NE(response.find("application/problem+json"), std::string::npos) << response;
  }
  expect_alive();
}

TEST_F(DaemonHostile, InvalidUtf8InParametersAndHeadersGets400) {
  const std::string mesh = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  for (const std::string query : {"format=obj&name=%FF", "format=%FF", "format=obj&name=a%00b"}) {
    RawConnection c(port());
    c.send("POST /v1/models?" + query + " HTTP/1.1\r\nHost: x\r\n" + auth() +
           "Content-Length: " + std::to_string(mesh.size()) + "\r\n\r\n" + mesh);
    const std::string response = c.read_response();
    EXPECT_EQ(status_of(response), 400) << query << ": " << response;
  }
  RawConnection c(port());
  c.send("GET /livez HTTP/1.1\r\nHost: x\r\nContent-Length: 1\xff\r\n\r\n");
  EXPECT_EQ(status_of(c.read_response()), 400);
  // Listing the owner's models still works (no name that cannot be serialized was stored).
  EXPECT_EQ(owner().get("/v1/models").status, 200);
}

TEST_F(DaemonHostile, DeeplyNestedJsonIsRefusedNotRecursedInto) {
  const std::string deep = "{\"payload\": \"ab\", \"x\": " + std::string(60000, '[') + std::string(60000, ']') + "}";
  RawConnection c(port());
  c.send("POST /v1/models/" + model_ + "/embed HTTP/1.1\r\nHost: x\r\n" + auth() +
         "Content-Type: application/json\r\n"
         "Content-Length: " +
         std::to_string(deep.size()) + "\r\n\r\n" + deep);
  const std::string response = c.read_response();
  EXPECT_EQ(status_of(response), 413) << response;  // far beyond the JSON body limit
  const std::string nested = "{\"payload\": \"ab\", \"x\": " + std::string(1000, '[') + std::string(1000, ']') + "}";
  RawConnection d(port());
  d.send("POST /v1/models/" + model_ + "/embed HTTP/1.1\r\nHost: x\r\n" + auth() +
         "Content-Length: " + std::to_string(nested.size()) + "\r\n\r\n" + nested);
  const std::string refused = d.read_response();
  EXPECT_EQ(status_of(refused), 400) << refused;
  EXPECT_NE(refused.find("nests deeper"), std::string::npos) << refused;
  expect_alive();
}

TEST_F(DaemonHostile, UnknownKeysAreRefusedNotStored) {
  const ApiResponse r =
      owner().post_json("/v1/models/" + model_ + "/embed", {{"payload", "ab"}, {"junk", std::string(1000, 'x')}});
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_NE(r.body.find("unknown key 'junk'"), std::string::npos) << r.body;
}

TEST_F(DaemonHostile, ARequestRefusedBeforeItsBodyNeverHasTheBodyTakenForARequest) {
  const std::string up = "POST /v1/models?format=obj HTTP/1.1\r\nHost: x\r\n";
  const std::string smuggled_length = std::to_string(std::string("GET /metrics HTTP/1.1\r\nHost: x\r\n\r\n").size());
  EXPECT_EQ(status_of(refused_with_smuggled_body(up + auth() + "Content-Length: 999999999999\r\n\r\n")), 413);
  EXPECT_EQ(status_of(refused_with_smuggled_body(
                up + auth() + "Content-Encoding: gzip\r\nContent-Length: " + smuggled_length + "\r\n\r\n")),
            415);
  EXPECT_EQ(status_of(refused_with_smuggled_body(up + "Content-Length: " + smuggled_length + "\r\n\r\n")), 401);
  EXPECT_EQ(status_of(refused_with_smuggled_body("POST /v1/models?format=nope HTTP/1.1\r\nHost: x\r\n" + auth() +
                                                 "Content-Length: " + smuggled_length + "\r\n\r\n")),
            400);
  EXPECT_EQ(status_of(refused_with_smuggled_body(
                "POST /v1/nothing HTTP/1.1\r\nHost: x\r\nContent-Length: " + smuggled_length + "\r\n\r\n")),
            404);
  EXPECT_EQ(status_of(refused_with_smuggled_body(up + auth() + "Transfer-Encoding: chunked\r\n\r\n")), 411);
}

TEST_F(DaemonHostile, AnEmptyUploadOrSuspectGets400NotAnInternalError) {
  for (const std::string& target :
       {std::string("/v1/models?format=obj"), "/v1/models/" + model_ + "/detect?format=obj"}) {
    RawConnection c(port());
    c.send("POST " + target + " HTTP/1.1\r\nHost: x\r\n" + auth() + "Content-Length: 0\r\n\r\n");
    const std::string answer = c.read_response();
    EXPECT_EQ(status_of(answer), 400) << answer;
    EXPECT_NE(answer.find("the body is empty"), std::string::npos) << answer;
  }
}

// Method names are the client's bytes: they never become metrics labels.
TEST_F(DaemonHostile, MetricsLabelsComeFromAFixedSet) {
  for (int k = 0; k < 5; ++k) {
    RawConnection c(port());
    c.send("BREW" + std::to_string(k) + " /livez HTTP/1.1\r\nHost: x\r\n\r\n");
    c.read_response();
  }
  const std::string metrics = ApiClient(port(), key_).get("/metrics").body;
  EXPECT_EQ(metrics.find("BREW"), std::string::npos);
  EXPECT_NE(metrics.find("method=\"other\""), std::string::npos);
}

TEST_F(DaemonHostile, EveryAnswerForbidsCachingAndTypeGuessing) {
  for (const char* path : {"/livez", "/v1/models", "/v1/nothing"}) {
    const ApiResponse r = ApiClient(port(), key_).get(path);
    EXPECT_EQ(r.header("Cache-Control"), "no-store") << path;
    EXPECT_EQ(r.header("X-Content-Type-Options"), "nosniff") << path;
  }
}

TEST_F(DaemonHostile, PipelinedRequestsAreAllAnsweredInOrder) {
  RawConnection c(port());
  c.send(
      "GET /livez HTTP/1.1\r\nHost: x\r\n\r\nGET /openapi.json HTTP/1.1\r\nHost: x\r\n\r\n"
      "GET /readyz HTTP/1.1\r\nHost: x\r\n\r\n");
  const std::string a = c.read_response(), b = c.read_response(), d = c.read_response();
  EXPECT_NE(a.find("\"ok\""), std::string::npos) << a;
  EXPECT_NE(b.find("\"openapi\""), std::string::npos) << b.substr(0, 200);
  EXPECT_NE(d.find("\"ready\""), std::string::npos) << d;
}

TEST_F(DaemonHostile, AmbiguousFramingIsRefused) {
  const std::vector<std::string> heads = {
      "POST /v1/owners HTTP/1.1\r\nHost: x\r\nContent-Length: 2\r\nContent-Length: 40\r\n\r\n{}",
      "POST /v1/owners HTTP/1.1\r\nHost: x\r\nContent-Length: 2\r\nContent-Length: 2\r\n\r\n{}",
      "POST /v1/owners HTTP/1.1\r\nHost: x\r\nContent-Length: +2\r\n\r\n{}",
      "POST /v1/owners HTTP/1.1\r\nHost: x\r\nTransfer-Encoding : chunked\r\n\r\n0\r\n\r\n",
      "POST /v1/owners HTTP/1.1\r\nHost: x\r\nContent-Length: 2\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n",
  };
  for (const std::string& head : heads) {
    RawConnection c(port());
    c.send(head);
    const std::string response = c.read_response();
    EXPECT_EQ(status_of(response) / 100, 4) << head << " → " << response;
    EXPECT_NE(status_of(response), 401) << "reached authentication: " << head;
    EXPECT_TRUE(c.closed_within(3s)) << head;
  }
  expect_alive();
}

TEST_F(DaemonHostile, AFloodOfHeadersIsCutOffAt16KiB) {
  RawConnection c(port());
  c.send("GET /livez HTTP/1.1\r\nHost: x\r\n");
  const std::string line = "X-Filler: " + std::string(1000, 'a') + "\r\n";
  bool accepted_all = true;
  for (int i = 0; i < 100'000 && accepted_all; ++i) accepted_all = c.send(line);  // 100 MB
  EXPECT_FALSE(accepted_all) << "100 MB of headers were read";
  expect_alive();
}

TEST_F(DaemonHostile, SlowAndIdleConnectionsDoNotStarveTheDaemon) {
  std::vector<std::unique_ptr<RawConnection>> held;  // idle, from four addresses (each under its cap)
  for (int i = 0; i < 500; ++i)
    held.push_back(std::make_unique<RawConnection>(port(), "127.0.0." + std::to_string(2 + i % 4)));
  std::vector<std::unique_ptr<RawConnection>> trickling;
  for (int i = 0; i < 32; ++i) {
    trickling.push_back(std::make_unique<RawConnection>(port()));
    trickling.back()->send("G");
  }
  for (int round = 0; round < 3; ++round) {
    for (auto& t : trickling) t->send("E");  // one byte per connection per second
    const auto start = std::chrono::steady_clock::now();
    const ApiResponse r = owner().get("/livez");
    const auto took = std::chrono::steady_clock::now() - start;
    EXPECT_EQ(r.status, 200);
    EXPECT_LT(took, 1s) << "/livez took " << std::chrono::duration<double>(took).count() << " s";
    std::this_thread::sleep_for(1s);
  }
  // A request head must arrive whole within 10 s: the tricklers are dropped.
  std::this_thread::sleep_for(8s);
  int closed = 0;
  for (auto& t : trickling) closed += t->closed_within(2s) ? 1 : 0;
  EXPECT_EQ(closed, 32);
}

// One address holding as many connections as its cap: its next one gets 503 and is closed, while
// another address is served at once.
TEST_F(DaemonHostile, OneClientHoldingManyConnectionsLeavesRoomForOthers) {
  std::vector<std::unique_ptr<RawConnection>> held;
  for (int i = 0; i < 256; ++i) held.push_back(std::make_unique<RawConnection>(port(), "127.0.0.9"));
  ASSERT_TRUE(held.back()->send("GET /livez HTTP/1.1\r\nHost: x\r\n\r\n"));
  EXPECT_EQ(status_of(held.back()->read_response()), 200);  // the last one within the cap is served
  RawConnection one_more(port(), "127.0.0.9");
  const std::string refused = one_more.read_response();
  EXPECT_EQ(status_of(refused), 503) << refused;
  EXPECT_NE(refused.find("too many connections from your address"), std::string::npos) << refused;
  EXPECT_TRUE(one_more.closed_within(3s));
  expect_alive();  // 127.0.0.1: another client
}

TEST_F(DaemonHostile, AHugeSuspectOffsetIsRefusedAtUpload) {
  const std::string far = "v 1e200 0 0\nv 1e200 1 0\nv 1e200 0 1\nf 1 2 3\n";
  const ApiResponse r = owner().post_bytes("/v1/models/" + model_ + "/detect?format=obj", far);
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_NE(r.body.find("1e30"), std::string::npos) << r.body;
}

TEST_F(DaemonHostile, ErrorsShownToClientsNeverNameServerPaths) {
  // A suspect far from the origin fails its detection job: the message is about the mesh.
  const std::string far = "v 1e12 0 0\nv 1e12 0.001 0\nv 1e12 0 0.001\nf 1 2 3\n";
  const ApiResponse r = owner().post_bytes("/v1/models/" + model_ + "/detect?format=obj", far);
  ASSERT_EQ(r.status, 202) << r.body;
  const auto job = owner().wait_job(r.json().at("job_id").get<std::string>());
  EXPECT_EQ(job.value("state", ""), "failed");
  const std::string error = job.value("error", "");
  EXPECT_NE(error.find("digits"), std::string::npos) << error;
  EXPECT_EQ(error.find(daemon_->data().string()), std::string::npos) << error;
}

// A model whose copies were handed out is deleted only when confirmed (its copies could never be
// traced again); then its files and its jobs' files go with it.
TEST_F(DaemonHostile, DeletingAModelWithCopiesNeedsConfirmingAndRemovesItsJobsFiles) {
  const std::string id =
      owner().upload_ready(file_bytes(procedural_file("creature")), "obj", "to-delete").at("id").get<std::string>();
  const ApiResponse e = owner().post_json("/v1/models/" + id + "/embed", {{"recipient", "r"}});
  const std::string job = e.json().at("job_id").get<std::string>();
  ASSERT_EQ(owner().wait_job(job).value("state", ""), "succeeded");
  const auto files = daemon_->data() / "blobs" / "jobs" / job;
  ASSERT_TRUE(std::filesystem::exists(files));
  for (const std::string& unconfirmed : {std::string(), std::string("?confirm=mdl_other")}) {
    const ApiResponse refused = owner().del("/v1/models/" + id + unconfirmed);
    EXPECT_EQ(refused.status, 409) << refused.body;
    EXPECT_NE(refused.body.find("1 copy handed out"), std::string::npos) << refused.body;
    EXPECT_EQ(owner().get("/v1/models/" + id + "/embeddings").json()["embeddings"].size(), 1u);
  }
  EXPECT_EQ(owner().del("/v1/models/" + id + "?confirm=" + id).status, 204);
  EXPECT_FALSE(std::filesystem::exists(files));
  EXPECT_FALSE(std::filesystem::exists(daemon_->data() / "blobs" / "models" / id));
}

TEST_F(DaemonHostile, ACopyStlCannotHoldFailsClearlyAndFreesItsPayload) {
  Mesh far = procedural_mesh("creature");
  far.V.col(0).array() += 1e6;  // fine in doubles, moved by ~0.06 (about 1 % of the creature) in 32-bit floats
  const std::string id = owner()
                             .upload_ready(write_mesh_to_memory(far, MeshFormat::ply, {.binary = true}), "ply", "far")
                             .at("id")
                             .get<std::string>();
  const ApiResponse stl = owner().post_json("/v1/models/" + id + "/embed", {{"payload", "abcd"}, {"format", "stl"}});
  ASSERT_EQ(stl.status, 202) << stl.body;
  const auto failed = owner().wait_job(stl.json().at("job_id").get<std::string>());
  EXPECT_EQ(failed.value("state", ""), "failed");
  EXPECT_NE(failed.value("error", "").find("32-bit floats"), std::string::npos) << failed.dump();
  EXPECT_TRUE(owner().get("/v1/models/" + id + "/embeddings").json()["embeddings"].empty());
  const ApiResponse ply = owner().post_json("/v1/models/" + id + "/embed", {{"payload", "abcd"}, {"format", "ply"}});
  ASSERT_EQ(ply.status, 202) << ply.body;  // the payload was not kept by the copy that was never made
  EXPECT_EQ(owner().wait_job(ply.json().at("job_id").get<std::string>()).value("state", ""), "succeeded");
}

TEST(DaemonStart, ASecondDaemonOnTheSameDataFolderIsRefused) {
  const auto data = temp_dir("twice");
  DaemonProcess first(data);
  const DaemonRun second = run_daemon_until_exit({"--listen", "127.0.0.1:0", "--data", data.string()},
                                                 std::string("MESHMARK_ADMIN_TOKEN=") + DaemonProcess::admin_token());
  EXPECT_NE(second.exit_status, 0);
  EXPECT_NE(second.output.find("another meshmarkd"), std::string::npos) << second.output;
  EXPECT_EQ(ApiClient(first.port(), "").get("/livez").status, 200);
}

TEST(DaemonStart, APortInUseIsRefused) {
  DaemonProcess first(temp_dir("port-a"));
  const DaemonRun second = run_daemon_until_exit(
      {"--listen", "127.0.0.1:" + std::to_string(first.port()), "--data", temp_dir("port-b").string()},
      std::string("MESHMARK_ADMIN_TOKEN=") + DaemonProcess::admin_token());
  EXPECT_NE(second.exit_status, 0);
  EXPECT_NE(second.output.find("in use"), std::string::npos) << second.output;
}

TEST(DaemonStart, AShortAdminTokenIsRefused) {
  const DaemonRun run = run_daemon_until_exit({"--listen", "127.0.0.1:0", "--data", temp_dir("short").string()},
                                              "MESHMARK_ADMIN_TOKEN=secret");
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.output.find("at least 16"), std::string::npos) << run.output;
  const DaemonRun repeated = run_daemon_until_exit({"--listen", "127.0.0.1:0", "--data", temp_dir("repeated").string()},
                                                   "MESHMARK_ADMIN_TOKEN=aaaaaaaaaaaaaaaa");
  EXPECT_EQ(repeated.exit_status, 2);
  EXPECT_NE(repeated.output.find("10 of them different"), std::string::npos) << repeated.output;
}

std::filesystem::path secret_file(const std::filesystem::path& folder, const std::string& name,
                                  const std::string& content) {
  const auto path = folder / name;
  std::ofstream(path) << content << "\n";
  std::filesystem::permissions(path, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  return path;
}

// Three daemons, each with its own data folder, on one store: the first records its master key's
// fingerprint; one given another key refuses to start; one given the same key serves.
TEST(DaemonStart, ADaemonGivenAnotherMasterKeyThanItsStoresRefuses) {
  const auto shared = temp_dir("cluster");
  const auto key_a = secret_file(shared, "a.key", "0123456789abcdef0123456789abcdef0123456789abcdef");
  const auto key_b = secret_file(shared, "b.key", "fedcba9876543210fedcba9876543210fedcba9876543210");
  const std::vector<std::string> on_store = {"--store", "sqlite:" + (shared / "meshmark.db").string(), "--blobs",
                                             "file:" + (shared / "blobs").string()};
  auto with = [&](const std::filesystem::path& key) {
    std::vector<std::string> flags = on_store;
    flags.insert(flags.end(), {"--master-key-file", key.string()});
    return flags;
  };
  DaemonProcess first(temp_dir("node-a"), with(key_a));
  std::vector<std::string> args = {"--listen", "127.0.0.1:0", "--data", temp_dir("node-b").string()};
  for (const std::string& flag : with(key_b)) args.push_back(flag);
  const DaemonRun other =
      run_daemon_until_exit(args, std::string("MESHMARK_ADMIN_TOKEN=") + DaemonProcess::admin_token());
  EXPECT_NE(other.exit_status, 0);
  EXPECT_NE(other.output.find("another master key"), std::string::npos) << other.output;
  EXPECT_NE(other.output.find(server::master_key_fingerprint("0123456789abcdef0123456789abcdef0123456789abcdef")),
            std::string::npos)
      << "the store's fingerprint is named: " << other.output;
  EXPECT_EQ(other.output.find("0123456789abcdef0123"), std::string::npos) << "never the key itself";
  DaemonProcess same(temp_dir("node-c"), with(key_a));
  EXPECT_EQ(ApiClient(same.port(), "").get("/readyz").status, 200);
}

TEST(DaemonStart, AMissingOrWeakConfiguredMasterKeyIsRefused) {
  const auto folder = temp_dir("keys");
  const std::string token = std::string("MESHMARK_ADMIN_TOKEN=") + DaemonProcess::admin_token();
  const DaemonRun missing = run_daemon_until_exit(
      {"--listen", "127.0.0.1:0", "--data", temp_dir("k1").string(), "--master-key-file", (folder / "none").string()},
      token);
  EXPECT_NE(missing.exit_status, 0);
  EXPECT_NE(missing.output.find("cannot read the master key"), std::string::npos) << missing.output;
  const DaemonRun weak = run_daemon_until_exit({"--listen", "127.0.0.1:0", "--data", temp_dir("k2").string(),
                                                "--master-key-file", secret_file(folder, "weak", "abc").string()},
                                               token);
  EXPECT_NE(weak.exit_status, 0);
  EXPECT_NE(weak.output.find("at least 32"), std::string::npos) << weak.output;
}

}  // namespace
}  // namespace meshmark::test
