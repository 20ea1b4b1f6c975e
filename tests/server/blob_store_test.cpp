// The contract of every BlobStore backend (storage_backends.hpp).
#include "server/store/blob_store.hpp"

#include <gtest/gtest.h>

#include <set>

#include "tests/server/daemon_process.hpp"
#include "tests/server/storage_backends.hpp"

namespace meshmark::server {
namespace {

class BlobContract : public ::testing::TestWithParam<test::BlobBackend> {
 protected:
  void SetUp() override {
    if (const std::string why = GetParam().absent(); !why.empty()) GTEST_SKIP() << why;
    blobs = GetParam().open(place);
  }
  std::filesystem::path place = test::temp_dir("blobs");
  std::unique_ptr<BlobStore> blobs;
};

TEST_P(BlobContract, WhatIsPutIsGotBackByteForByte) {
  std::string bytes(70'000, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 131 % 256);
  blobs->put("models/mdl_1/upload", bytes);
  EXPECT_EQ(blobs->get("models/mdl_1/upload"), bytes);
  blobs->put("models/mdl_1/upload", "replaced");
  EXPECT_EQ(blobs->get("models/mdl_1/upload"), "replaced");
  blobs->put("models/mdl_1/empty", "");
  EXPECT_EQ(blobs->get("models/mdl_1/empty"), "");
  EXPECT_FALSE(blobs->get("models/mdl_1/absent"));
}

TEST_P(BlobContract, BlobsOutliveTheirClient) {
  blobs->put("jobs/job_1/output.ply", "ply");
  blobs.reset();
  EXPECT_EQ(GetParam().open(place)->get("jobs/job_1/output.ply"), "ply");
}

TEST_P(BlobContract, RemovingAPrefixRemovesThatFolderOnly) {
  blobs->put("models/mdl_1/original.ply", "a");
  blobs->put("models/mdl_1/prepared.bin", "b");
  blobs->put("models/mdl_10/original.ply", "c");
  blobs->remove_prefix("models/mdl_1");
  EXPECT_FALSE(blobs->get("models/mdl_1/original.ply"));
  EXPECT_FALSE(blobs->get("models/mdl_1/prepared.bin"));
  EXPECT_EQ(blobs->get("models/mdl_10/original.ply"), "c") << "a prefix is a folder, not a string";
  blobs->remove_prefix("models/mdl_404");  // nothing there: no error
}

// A listing names the blobs of the folder and below, by their keys (never the store's own prefix),
// each with when it was written.
TEST_P(BlobContract, AListingNamesEveryBlobOfAFolderWithItsTime) {
  const auto before = std::chrono::system_clock::now() - std::chrono::minutes(5);
  blobs->put("models/mdl_1/original.ply", "a");
  blobs->put("models/mdl_2/upload", "b");
  blobs->put("jobs/job_1/output.ply", "c");
  std::set<std::string> keys;
  blobs->list("models", [&](const StoredBlob& blob) {
    keys.insert(blob.key);
    EXPECT_GT(blob.modified, before) << blob.key;
    EXPECT_LT(blob.modified, before + std::chrono::minutes(10)) << blob.key;
  });
  EXPECT_EQ(keys, (std::set<std::string>{"models/mdl_1/original.ply", "models/mdl_2/upload"}));
  blobs->list("absent", [](const StoredBlob& blob) { ADD_FAILURE() << blob.key; });
}

TEST_P(BlobContract, KeysThatCouldEscapeAreRefused) {
  for (const char* key : {"", "/etc/passwd", "models/../../x", ".."})
    EXPECT_THROW(blobs->put(key, "x"), std::invalid_argument) << key;
}

INSTANTIATE_TEST_SUITE_P(Backends, BlobContract, ::testing::ValuesIn(test::blob_backends()),
                         [](const auto& info) { return test::backend_name(info.param); });

}  // namespace
}  // namespace meshmark::server
