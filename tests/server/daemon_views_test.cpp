// What the web console reads: the console's own files with their security policy, the 3D
// previews of a model, a copy and an aligned suspect, and a detection's evidence report.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <regex>

#include "core/attacks/similarity_transform.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"
#include "tests/server/api_client.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

// Markup in every name a user gives: the report must show it as text.
constexpr const char* kModelName = "creature <b>bold</b>";
constexpr const char* kRecipient = "partner <img src=x onerror=alert(1)>";
constexpr const char* kRequester = "Ana <i>licensing</i>";

class DaemonViews : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon_ = new DaemonProcess(temp_dir("views"));
    key_ = ApiClient(daemon_->port(), "").create_owner(DaemonProcess::admin_token(), "studio");
    model_ = owner().upload_ready(file_bytes(procedural_file("creature")), "obj", kModelName);
    const ApiResponse r =
        owner().post_json(path() + "/embed", {{"recipient", kRecipient}, {"requested_by", kRequester}});
    copy_job_ = owner().wait_job(r.json().at("job_id").get<std::string>());
  }
  static void TearDownTestSuite() {
    delete daemon_;
    daemon_ = nullptr;
  }
  static ApiClient owner() { return ApiClient(daemon_->port(), key_); }
  static std::string path() { return "/v1/models/" + model_.at("id").get<std::string>(); }
  static std::string copy_path() { return "/v1/jobs/" + copy_job_.at("id").get<std::string>(); }

  static DaemonProcess* daemon_;
  static std::string key_;
  static nlohmann::json model_, copy_job_;
};

DaemonProcess* DaemonViews::daemon_ = nullptr;
std::string DaemonViews::key_;
nlohmann::json DaemonViews::model_, DaemonViews::copy_job_;

Mesh preview_mesh(const ApiResponse& r) {
  EXPECT_EQ(r.status, 200) << r.body.substr(0, 300);
  return read_mesh_from_memory(r.body, MeshFormat::ply).mesh;
}

TEST_F(DaemonViews, ConsoleIsServedWithAPolicyThatForbidsInlineScripts) {
  const ApiResponse page = ApiClient(daemon_->port(), "").get("/");
  ASSERT_EQ(page.status, 200);
  EXPECT_EQ(page.header("Content-Type"), "text/html; charset=utf-8");
  const std::string policy = page.header("Content-Security-Policy");
  EXPECT_NE(policy.find("script-src 'self'"), std::string::npos) << policy;
  EXPECT_EQ(policy.find("unsafe-inline"), std::string::npos) << policy;
  EXPECT_EQ(policy.find("unsafe-eval"), std::string::npos) << policy;
  // Every script the page loads comes from a file the daemon serves; none is inline.
  const std::regex script("<script([^>]*)>");
  int scripts = 0;
  for (auto it = std::sregex_iterator(page.body.begin(), page.body.end(), script); it != std::sregex_iterator(); ++it) {
    const std::string attributes = (*it)[1];
    const std::smatch src = [&] {
      std::smatch m;
      std::regex_search(attributes, m, std::regex("src=\"([^\"]+)\""));
      return m;
    }();
    ASSERT_FALSE(src.empty()) << "an inline script: " << it->str();
    EXPECT_EQ(ApiClient(daemon_->port(), "").get(src[1]).status, 200) << src[1];
    ++scripts;
  }
  EXPECT_GE(scripts, 1);
  for (const char* file : {"/console/api.js", "/console/viewer.js", "/console/vendor/three.module.js",
                           "/console/vendor/three.core.js", "/console/vendor/OrbitControls.js", "/console/style.css"}) {
    const ApiResponse r = ApiClient(daemon_->port(), "").get(file);
    EXPECT_EQ(r.status, 200) << file;
    EXPECT_GT(r.body.size(), 100u) << file;
  }
  // The bare module name 'three' resolves only through an import map, which the policy forbids.
  EXPECT_EQ(ApiClient(daemon_->port(), "").get("/console/vendor/OrbitControls.js").body.find("from 'three'"),
            std::string::npos);
  EXPECT_EQ(ApiClient(daemon_->port(), "").get("/console/nothing.js").status, 404);
}

TEST_F(DaemonViews, ModelPreviewIsItsSurfaceAndNeedsTheOwnersKey) {
  const Mesh surface = preview_mesh(owner().get(path() + "/preview"));
  EXPECT_EQ(surface.V.rows(), model_.value("vertices", 0));
  EXPECT_EQ(surface.F.rows(), model_.value("faces", 0));
  EXPECT_EQ(ApiClient(daemon_->port(), "").get(path() + "/preview").status, 401);
  const std::string other = ApiClient(daemon_->port(), "").create_owner(DaemonProcess::admin_token(), "other");
  EXPECT_EQ(ApiClient(daemon_->port(), other).get(path() + "/preview").status, 404);
}

TEST_F(DaemonViews, CopyPreviewCarriesTheMarksDisplacementAlongTheNormals) {
  ASSERT_EQ(copy_job_.value("state", ""), "succeeded") << copy_job_.dump();
  const ApiResponse r = owner().get(copy_path() + "/preview");
  ASSERT_EQ(r.status, 200);
  const std::size_t header_end = r.body.find("end_header\n") + 11;
  ASSERT_NE(r.body.substr(0, header_end).find("property float displacement"), std::string::npos);
  const auto vertices = static_cast<std::size_t>(model_.value("vertices", 0));
  double sum_squares = 0, largest = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    float d = 0;
    std::memcpy(&d, r.body.data() + header_end + v * 16 + 12, 4);
    sum_squares += double(d) * d;
    largest = std::max(largest, std::abs(double(d)));
  }
  const double rms = std::sqrt(sum_squares / vertices);
  // The default strength is 0.05 % RMS of the diagonal, most of it along the normals.
  EXPECT_GT(rms, 0.01);
  EXPECT_LT(rms, 0.1);
  EXPECT_LT(largest, 1.0);
}

TEST_F(DaemonViews, EvidenceReportNamesTheRecipientAsTextWithPicturesAndDigests) {
  const ApiResponse copy = owner().get(copy_path() + "/result");
  const Mesh marked = read_mesh_from_memory(copy.body, MeshFormat::obj).mesh;
  const Mesh suspect = transform_mesh(marked, random_similarity(marked, 7));
  const std::string bytes = write_mesh_to_memory(suspect, MeshFormat::ply, {.binary = true});
  const ApiResponse posted = owner().post_bytes(path() + "/detect?format=ply", bytes);
  ASSERT_EQ(posted.status, 202) << posted.body;
  const nlohmann::json job = owner().wait_job(posted.json().at("job_id").get<std::string>());
  ASSERT_EQ(job.value("state", ""), "succeeded") << job.dump();
  const std::string detection = "/v1/jobs/" + job.at("id").get<std::string>();

  const ApiResponse report = owner().get(detection + "/report");
  ASSERT_EQ(report.status, 200);
  EXPECT_EQ(report.header("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(report.header("Content-Security-Policy").find("default-src 'none'"), std::string::npos);
  const std::string& html = report.body;
  EXPECT_NE(html.find("handed out to partner &lt;img src=x onerror=alert(1)&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<img src=x"), std::string::npos) << "a name went into the page as markup";
  EXPECT_NE(html.find("creature &lt;b&gt;bold&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(html.find("Copy asked for by</th><td>Ana &lt;i&gt;licensing&lt;/i&gt;<"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_GE(std::count(html.begin(), html.end(), '\n'), 10);
  std::size_t pictures = 0;
  for (std::size_t at = 0; (at = html.find("data:image/png;base64,", at)) != std::string::npos; ++at) ++pictures;
  EXPECT_EQ(pictures, 4u);
  EXPECT_NE(html.find(job["result"]["match"].value("payload", "?")), std::string::npos);
  // The suspect's file digest, as uploaded (SHA-256, hex).
  EXPECT_TRUE(std::regex_search(html, std::regex("SHA-256 of the suspect&#39;s file</th><td>[0-9a-f]{64}<")));
  EXPECT_EQ(job["result"]["match"].value("bit_errors", -1), 0);

  // The aligned suspect lies on the original: its bounding box matches the model's.
  const Mesh aligned = preview_mesh(owner().get(detection + "/preview"));
  const Mesh original = preview_mesh(owner().get(path() + "/preview"));
  const double diagonal = (original.V.colwise().maxCoeff() - original.V.colwise().minCoeff()).norm();
  EXPECT_LT((aligned.V.colwise().maxCoeff() - original.V.colwise().maxCoeff()).norm(), 0.01 * diagonal);
  EXPECT_LT((aligned.V.colwise().minCoeff() - original.V.colwise().minCoeff()).norm(), 0.01 * diagonal);

  EXPECT_EQ(owner().get(copy_path() + "/report").status, 409) << "a report is made of a detection";
  EXPECT_EQ(owner().get("/v1/jobs/job_nothing/report").status, 404);
}

}  // namespace
}  // namespace meshmark::test
