#include "server/store/orphan_sweep.hpp"

#include <gtest/gtest.h>

#include "server/store/blob_keys.hpp"
#include "server/store/sqlite_store.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/server/storage_backends.hpp"
#include "tests/server/store_records.hpp"

namespace meshmark::server {
namespace {

// Over every blob backend: a store with one model and its prepare job; blobs of it, of a model
// and a job whose rows are gone, and files the daemon did not name.
class OrphanSweep : public ::testing::TestWithParam<test::BlobBackend> {
 protected:
  void SetUp() override {
    if (const std::string why = GetParam().absent(); !why.empty()) GTEST_SKIP() << why;
    blobs = GetParam().open(test::temp_dir("sweep-blobs"));
    clock.set(std::chrono::system_clock::now());
    store->insert_owner({"own_1", "o", "t"}, "h");
    store->insert_model(test::preparing_model("mdl_kept", "own_1"),
                        test::job_record("job_kept", "own_1", "mdl_kept", JobKind::prepare));
    for (const std::string& key :
         {original_key("mdl_kept"), output_key("job_kept", "ply"), original_key("mdl_gone"), upload_key("mdl_gone"),
          output_key("job_gone", "ply"), std::string("models/loose"), std::string("elsewhere/mdl_gone/x")})
      blobs->put(key, "bytes");
  }
  bool present(const std::string& key) { return blobs->get(key).has_value(); }

  test::ManualClock clock;
  std::unique_ptr<Store> store = std::make_unique<SqliteStore>(test::temp_dir("sweep-store") / "meshmark.db", clock);
  std::unique_ptr<BlobStore> blobs;
};

TEST_P(OrphanSweep, BlobsWithoutARecordGoOnceOlderThanTheGrace) {
  const SweepReport fresh = sweep_orphan_blobs(*store, *blobs, clock, std::chrono::hours(1));
  EXPECT_EQ(fresh.examined, 6u);  // models/ and jobs/ only
  EXPECT_EQ(fresh.removed, 0u) << "a blob written moments ago may be about to get its row";
  EXPECT_TRUE(present(original_key("mdl_gone")));

  clock.advance(std::chrono::hours(2));
  const SweepReport late = sweep_orphan_blobs(*store, *blobs, clock, std::chrono::hours(1));
  EXPECT_EQ(late.removed, 3u);
  for (const std::string& gone : {original_key("mdl_gone"), upload_key("mdl_gone"), output_key("job_gone", "ply")})
    EXPECT_FALSE(present(gone)) << gone;
  for (const std::string& kept : {original_key("mdl_kept"), output_key("job_kept", "ply"), std::string("models/loose"),
                                  std::string("elsewhere/mdl_gone/x")})
    EXPECT_TRUE(present(kept)) << kept;
}

TEST_P(OrphanSweep, ADeletedModelsFilesGoWithItsJobs) {
  ASSERT_TRUE(store->delete_model("own_1", "mdl_kept"));
  clock.advance(std::chrono::hours(2));
  EXPECT_EQ(sweep_orphan_blobs(*store, *blobs, clock, std::chrono::hours(1)).removed, 5u);
  EXPECT_FALSE(present(original_key("mdl_kept")));
  EXPECT_FALSE(present(output_key("job_kept", "ply")));
}

INSTANTIATE_TEST_SUITE_P(Backends, OrphanSweep, ::testing::ValuesIn(test::blob_backends()),
                         [](const auto& info) { return test::backend_name(info.param); });

}  // namespace
}  // namespace meshmark::server
