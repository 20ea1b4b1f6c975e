// What only an object store can do wrong: credentials, and a server that does not answer.
#include "server/store/s3_blob_store.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

#include "server/store/open_storage.hpp"
#include "server/store/storage_error.hpp"

namespace meshmark::server {
namespace {

StorageError::Kind failure_of(BlobStore& blobs) {
  try {
    blobs.put("models/mdl_1/original.ply", "ply");
  } catch (const StorageError& e) {
    return e.kind();
  }
  ADD_FAILURE() << "the write succeeded";
  return StorageError::Kind::full;
}

// s3rver checks the access key id but not a SigV4 signature (its source: "unimplemented"); AWS,
// MinIO and Ceph check both, and refuse either the same way.
TEST(S3BlobStore, UnknownCredentialsAreAPermanentFailure) {
  const char* endpoint = std::getenv("MESHMARK_TEST_S3_ENDPOINT");
  if (!endpoint) GTEST_SKIP() << "no S3-compatible server (MESHMARK_TEST_S3_ENDPOINT)";
  S3BlobStore blobs({endpoint, "us-east-1", "meshmark-test", "wrong", "NOT-A-KEY", "not-the-secret"});
  EXPECT_EQ(failure_of(blobs), StorageError::Kind::permanent);
}

TEST(S3BlobStore, AServerThatDoesNotAnswerIsUnavailable) {
  S3BlobStore blobs({"http://127.0.0.1:1", "us-east-1", "bucket", "", "key", "secret"});
  EXPECT_EQ(failure_of(blobs), StorageError::Kind::unavailable);
}

TEST(S3BlobStore, ALocationNamesItsBucketPrefixAndCredentials) {
  ::setenv("AWS_ACCESS_KEY_ID", "AK", 1);
  ::setenv("AWS_SECRET_ACCESS_KEY", "SK", 1);
  ::setenv("MESHMARK_S3_ENDPOINT", "http://minio:9000/", 1);
  const S3Location l = s3_location_from("s3://meshes/studio/a/");
  EXPECT_EQ(l.bucket, "meshes");
  EXPECT_EQ(l.prefix, "studio/a");
  EXPECT_EQ(l.endpoint, "http://minio:9000");
  EXPECT_EQ(l.access_key, "AK");
  EXPECT_THROW(s3_location_from("s3:///x"), std::invalid_argument);
  ::unsetenv("AWS_SECRET_ACCESS_KEY");
  EXPECT_THROW(open_blob_store("s3://meshes", "data"), std::invalid_argument);
  ::unsetenv("AWS_ACCESS_KEY_ID");
  ::unsetenv("MESHMARK_S3_ENDPOINT");
  EXPECT_THROW(open_blob_store("ftp://x", "data"), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark::server
