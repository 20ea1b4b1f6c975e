#include "server/store/s3_blob_store.hpp"

#include <curl/curl.h>

#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "core/util/keyed_random.hpp"
#include "server/clock.hpp"
#include "server/store/storage_error.hpp"

namespace meshmark::server {

namespace {

std::string environment(const char* name, const std::string& fallback = "") {
  const char* value = std::getenv(name);
  return value && *value ? value : fallback;
}

// Every character but the unreserved ones, percent-encoded (what SigV4's canonical form wants).
std::string escaped(const std::string& text) {
  char* out = curl_easy_escape(nullptr, text.data(), static_cast<int>(text.size()));
  if (!out) throw std::bad_alloc();
  std::string result(out);
  curl_free(out);
  return result;
}

// A key's segments escaped, its slashes kept.
std::string escaped_path(const std::string& key) {
  std::string out;
  std::size_t start = 0;
  while (true) {
    const auto slash = key.find('/', start);
    out += escaped(key.substr(start, slash - start));
    if (slash == std::string::npos) return out;
    out += '/';
    start = slash + 1;
  }
}

std::size_t collect(char* data, std::size_t size, std::size_t count, void* into) {
  static_cast<std::string*>(into)->append(data, size * count);
  return size * count;
}

// The text of each <tag>…</tag> in an S3 XML answer, entities decoded.
std::vector<std::string> xml_values(const std::string& xml, const std::string& tag) {
  std::vector<std::string> values;
  const std::string open = "<" + tag + ">", close = "</" + tag + ">";
  for (std::size_t at = xml.find(open); at != std::string::npos; at = xml.find(open, at)) {
    at += open.size();
    const auto end = xml.find(close, at);
    if (end == std::string::npos) break;
    std::string value = xml.substr(at, end - at);
    for (const auto& [entity, character] :
         {std::pair{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}, {"&amp;", "&"}})
      for (std::size_t p = value.find(entity); p != std::string::npos; p = value.find(entity, p + 1))
        value.replace(p, std::string(entity).size(), character);
    values.push_back(std::move(value));
  }
  return values;
}

[[noreturn]] void refuse(const S3BlobStore::Response& r, const std::string& what) {
  const auto code = xml_values(r.body, "Code");
  const std::string detail =
      "object store: " + what + ": HTTP " + std::to_string(r.status) + (code.empty() ? "" : " " + code.front());
  const bool later = r.status >= 500 || r.status == 429 || (!code.empty() && code.front() == "SlowDown");
  throw StorageError(detail, later ? StorageError::Kind::unavailable : StorageError::Kind::permanent);
}

void global_init() {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

}  // namespace

S3Location s3_location_from(const std::string& location) {
  const std::string scheme = "s3://";
  if (location.rfind(scheme, 0) != 0) throw std::invalid_argument("--blobs: an object store is s3://BUCKET/PREFIX");
  S3Location l;
  const std::string rest = location.substr(scheme.size());
  const auto slash = rest.find('/');
  l.bucket = rest.substr(0, slash);
  if (slash != std::string::npos) l.prefix = rest.substr(slash + 1);
  while (!l.prefix.empty() && l.prefix.back() == '/') l.prefix.pop_back();
  if (l.bucket.empty()) throw std::invalid_argument("--blobs: s3:// needs a bucket (s3://BUCKET/PREFIX)");
  l.region = environment("MESHMARK_S3_REGION", environment("AWS_REGION", "us-east-1"));
  l.endpoint = environment("MESHMARK_S3_ENDPOINT", "https://s3." + l.region + ".amazonaws.com");
  while (!l.endpoint.empty() && l.endpoint.back() == '/') l.endpoint.pop_back();
  l.access_key = environment("AWS_ACCESS_KEY_ID");
  l.secret_key = environment("AWS_SECRET_ACCESS_KEY");
  if (l.access_key.empty() || l.secret_key.empty())
    throw std::invalid_argument("--blobs s3://: set AWS_ACCESS_KEY_ID and AWS_SECRET_ACCESS_KEY");
  return l;
}

S3BlobStore::S3BlobStore(S3Location location) : location_(std::move(location)) { global_init(); }

std::string S3BlobStore::object_key(const std::string& key) const {
  check_blob_key(key);
  return location_.prefix.empty() ? key : location_.prefix + "/" + key;
}

S3BlobStore::Response S3BlobStore::send(const std::string& method, const std::string& path, const std::string& query,
                                        const std::string* body) const {
  const std::unique_ptr<CURL, void (*)(CURL*)> curl(curl_easy_init(), curl_easy_cleanup);
  if (!curl) throw StorageError("object store: cannot start a request", StorageError::Kind::unavailable);
  const std::string url = location_.endpoint + "/" + escaped(location_.bucket) +
                          (path.empty() ? "" : "/" + escaped_path(path)) + (query.empty() ? "" : "?" + query);
  const std::string sigv4 = "aws:amz:" + location_.region + ":s3";
  const std::string credentials = location_.access_key + ":" + location_.secret_key;
  curl_slist* headers = nullptr;
  headers = curl_slist_append(headers, ("x-amz-content-sha256: " + sha256_hex(body ? *body : "")).c_str());
  headers = curl_slist_append(headers, "Expect:");  // no 100-continue round trip
  if (body) headers = curl_slist_append(headers, "Content-Type: application/octet-stream");
  const std::unique_ptr<curl_slist, void (*)(curl_slist*)> header_list(headers, curl_slist_free_all);
  Response response;
  CURL* c = curl.get();
  curl_easy_setopt(c, CURLOPT_URL, url.c_str());
  curl_easy_setopt(c, CURLOPT_CUSTOMREQUEST, method.c_str());
  curl_easy_setopt(c, CURLOPT_AWS_SIGV4, sigv4.c_str());
  curl_easy_setopt(c, CURLOPT_USERPWD, credentials.c_str());
  curl_easy_setopt(c, CURLOPT_HTTPHEADER, header_list.get());
  curl_easy_setopt(c, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(c, CURLOPT_CONNECTTIMEOUT, 10L);
  curl_easy_setopt(c, CURLOPT_LOW_SPEED_LIMIT, 1024L);  // a stalled transfer fails, a long one does not
  curl_easy_setopt(c, CURLOPT_LOW_SPEED_TIME, 30L);
  curl_easy_setopt(c, CURLOPT_WRITEFUNCTION, collect);
  curl_easy_setopt(c, CURLOPT_WRITEDATA, &response.body);
  if (body) {
    curl_easy_setopt(c, CURLOPT_POSTFIELDS, body->data());
    curl_easy_setopt(c, CURLOPT_POSTFIELDSIZE_LARGE, static_cast<curl_off_t>(body->size()));
  } else if (method == "HEAD") {
    curl_easy_setopt(c, CURLOPT_NOBODY, 1L);
  }
  if (const CURLcode rc = curl_easy_perform(c); rc != CURLE_OK)
    throw StorageError("object store: " + method + " " + path + ": " + curl_easy_strerror(rc),
                       StorageError::Kind::unavailable);
  curl_easy_getinfo(c, CURLINFO_RESPONSE_CODE, &response.status);
  return response;
}

void S3BlobStore::put(const std::string& key, const std::string& bytes) {
  const Response r = send("PUT", object_key(key), "", &bytes);
  if (r.status != 200) refuse(r, "cannot write " + key);
}

std::optional<std::string> S3BlobStore::get(const std::string& key) {
  Response r = send("GET", object_key(key), "", nullptr);
  if (r.status == 404) return std::nullopt;
  if (r.status != 200) refuse(r, "cannot read " + key);
  return std::move(r.body);
}

void S3BlobStore::remove_object(const std::string& key) const {
  const Response r = send("DELETE", key, "", nullptr);
  if (r.status != 204 && r.status != 200 && r.status != 404) refuse(r, "cannot remove " + key);
}

void S3BlobStore::remove_prefix(const std::string& prefix) {
  remove_object(object_key(prefix));
  list(prefix, [this](const StoredBlob& blob) { remove_object(object_key(blob.key)); });
}

void S3BlobStore::list(const std::string& folder, const BlobVisitor& visit) {
  const std::string listed_prefix = object_key(folder) + "/";
  const std::size_t ours = location_.prefix.empty() ? 0 : location_.prefix.size() + 1;
  std::string token;
  do {  // ListObjectsV2, a page at a time; the query's parameters in SigV4's sorted order
    const std::string query = (token.empty() ? "" : "continuation-token=" + escaped(token) + "&") +
                              "list-type=2&prefix=" + escaped(listed_prefix);
    const Response page = send("GET", "", query, nullptr);
    if (page.status != 200) refuse(page, "cannot list " + folder);
    const auto keys = xml_values(page.body, "Key");
    const auto times = xml_values(page.body, "LastModified");  // one per <Contents>, as its Key
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const auto modified = i < times.size() ? parse_iso8601(times[i]) : std::nullopt;
      visit({keys[i].substr(ours), modified.value_or(std::chrono::system_clock::now())});
    }
    const auto truncated = xml_values(page.body, "IsTruncated");
    const auto next = xml_values(page.body, "NextContinuationToken");
    token = !truncated.empty() && truncated.front() == "true" && !next.empty() ? next.front() : "";
  } while (!token.empty());
}

}  // namespace meshmark::server
