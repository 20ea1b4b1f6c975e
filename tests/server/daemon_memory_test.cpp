// The daemon's memory ceiling, on the real daemon: large uploads at once are admitted only as far
// as the ceiling has room (the rest get 503 + Retry-After), its peak stays under the ceiling, and
// another owner's small requests are answered meanwhile.

#include <gtest/gtest.h>

#include <fstream>
#include <future>
#include <thread>

#include "core/attacks/subdivide.hpp"
#include "core/io/write_mesh.hpp"
#include "tests/server/api_client.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

using namespace std::chrono_literals;

// A sanitizer's shadow memory is not the daemon's (GCC names the sanitizers by macro, clang by feature).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MESHMARK_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define MESHMARK_SANITIZED 1
#endif
#endif
#ifdef MESHMARK_SANITIZED
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

// The peak resident memory of a process (VmHWM), in MiB.
std::size_t peak_resident_mib(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  std::size_t kib = 0;
  while (status >> key)
    if (key == "VmHWM:" && status >> kib) return kib >> 10;
  return 0;
}

TEST(DaemonMemory, LargeUploadsAtOnceStayUnderTheCeilingAndOthersAreAnswered) {
  constexpr int kCeilingMib = 350;
  DaemonProcess daemon(temp_dir("memory"), {"--memory-ceiling-mb", std::to_string(kCeilingMib), "--workers", "1"});
  const ApiClient studio(daemon.port(),
                         ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "bulk"));
  const ApiClient other(daemon.port(),
                        ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "other"));
  // 164k vertices as binary PLY (8 MB): one such upload takes most of the ceiling, its real
  // use about a third of it, so six at once would pass the ceiling if all were read together.
  const Mesh large = subdivide(procedural_mesh("creature_large"), SubdivisionScheme::loop, 2);
  const std::string bytes = write_mesh_to_memory(large, MeshFormat::ply, {.binary = true});

  std::vector<std::future<ApiResponse>> uploads;
  for (int i = 0; i < 6; ++i)
    uploads.push_back(
        std::async(std::launch::async, [&] { return studio.post_bytes("/v1/models?format=ply", bytes); }));
  const std::string small = file_bytes(procedural_file("creature", "obj").string());
  for (int i = 0; i < 5; ++i) {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(other.get("/v1/models").status, 200);
    EXPECT_EQ(other.post_bytes("/v1/models?format=obj", small).status, 202);
    EXPECT_LT(std::chrono::steady_clock::now() - start, 5s) << "another owner waited for the large uploads";
  }
  int admitted = 0, refused = 0;
  for (auto& upload : uploads) {
    const ApiResponse r = upload.get();
    ASSERT_TRUE(r.status == 202 || r.status == 503) << r.status << " " << r.body;
    if (r.status == 202) ++admitted;
    if (r.status == 503) {
      ++refused;
      EXPECT_FALSE(r.header("Retry-After").empty());
      EXPECT_NE(r.body.find("memory"), std::string::npos) << r.body;
    }
  }
  EXPECT_GE(admitted, 1);
  EXPECT_GE(refused, 1) << "six uploads of most of the ceiling were all read";
  const std::string metrics = other.get("/metrics").body;
  EXPECT_NE(metrics.find("meshmark_memory_ceiling_bytes " + std::to_string(kCeilingMib << 20)), std::string::npos);
  if (!kSanitized) {
    EXPECT_LT(peak_resident_mib(daemon.pid()), kCeilingMib);
  }
}

TEST(DaemonMemory, AnUploadThatCouldNeverFitTheCeilingIsRefusedAsTooLarge) {
  DaemonProcess daemon(temp_dir("memory-small"), {"--memory-ceiling-mb", "64"});
  const ApiClient owner(daemon.port(), ApiClient(daemon.port(), "").create_owner(DaemonProcess::admin_token(), "o"));
  const Mesh large = subdivide(procedural_mesh("creature_large"), SubdivisionScheme::loop, 2);
  const ApiResponse r =
      owner.post_bytes("/v1/models?format=ply", write_mesh_to_memory(large, MeshFormat::ply, {.binary = true}));
  EXPECT_EQ(r.status, 413) << r.body;
  EXPECT_NE(r.body.find("memory ceiling is 64 MiB"), std::string::npos) << r.body;
}

}  // namespace
}  // namespace meshmark::test
