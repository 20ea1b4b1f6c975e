#pragma once
// Blobs in an S3-compatible object store (AWS S3, MinIO, Ceph RGW, …), path-style, every request
// signed by libcurl's own AWS Signature V4 (CURLOPT_AWS_SIGV4) with the payload's SHA-256 in
// x-amz-content-sha256. A key "models/x/original.ply" is the object PREFIX/models/x/original.ply.

#include <string>

#include "server/store/blob_store.hpp"

namespace meshmark::server {

struct S3Location {
  std::string endpoint;  ///< "https://s3.eu-west-1.amazonaws.com", "http://127.0.0.1:9000"
  std::string region = "us-east-1";
  std::string bucket;
  std::string prefix;  ///< the folder inside the bucket ("" or ending without '/')
  std::string access_key, secret_key;
};

/// "s3://BUCKET/PREFIX" with the endpoint from MESHMARK_S3_ENDPOINT (default AWS's for the
/// region), the region from MESHMARK_S3_REGION or AWS_REGION (default us-east-1), and the
/// credentials from AWS_ACCESS_KEY_ID and AWS_SECRET_ACCESS_KEY. Throws std::invalid_argument
/// saying what is missing.
S3Location s3_location_from(const std::string& location);

class S3BlobStore : public BlobStore {
 public:
  explicit S3BlobStore(S3Location location);
  void put(const std::string& key, const std::string& bytes) override;
  std::optional<std::string> get(const std::string& key) override;
  void remove_prefix(const std::string& prefix) override;
  void list(const std::string& folder, const BlobVisitor& visit) override;

  struct Response {
    long status = 0;
    std::string body;
  };

 private:
  // One signed request; `path` is the object's key (escaped here) or empty for the bucket.
  Response send(const std::string& method, const std::string& path, const std::string& query,
                const std::string* body) const;
  std::string object_key(const std::string& key) const;
  void remove_object(const std::string& object_key) const;

  S3Location location_;
};

}  // namespace meshmark::server
