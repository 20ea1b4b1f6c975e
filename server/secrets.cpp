#include "server/secrets.hpp"

#include <fcntl.h>
#include <openssl/rand.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/util/atomic_file.hpp"
#include "core/util/keyed_random.hpp"

namespace meshmark::server {

std::string random_hex(std::size_t bytes) {
  std::vector<unsigned char> raw(bytes);
  if (RAND_bytes(raw.data(), static_cast<int>(raw.size())) != 1)
    throw std::runtime_error("the system random generator failed");
  return to_hex(raw.data(), raw.size());
}

std::string new_id(const std::string& prefix) { return prefix + random_hex(10); }

std::string new_api_key() { return "mmk_" + random_hex(32); }

std::string hash_api_key(const std::string& key) { return sha256_hex(key); }

bool constant_time_equal(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

std::string load_or_create_secret(const std::filesystem::path& file, std::size_t bytes, bool& created) {
  created = false;
  struct stat info {};
  if (::stat(file.c_str(), &info) == 0) {
    if ((info.st_mode & 077) != 0)
      throw std::runtime_error(file.string() + " is readable by others (mode " + std::to_string(info.st_mode & 0777) +
                               "); chmod 600 it");
    std::ifstream in(file);
    std::string content;
    std::getline(in, content);
    if (content.empty()) throw std::runtime_error(file.string() + " is empty");
    return content;
  }
  std::string content = random_hex(bytes);
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) throw std::runtime_error("cannot create " + file.string());
  const std::string line = content + "\n";
  const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size()) && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) throw std::runtime_error("cannot write " + file.string());
  created = true;
  return content;
}

std::string owner_watermark_key(const std::string& master_key, const std::string& owner_id) {
  const auto mac = hmac_sha256(master_key, "meshmark owner key/" + owner_id);
  return to_hex(mac.data(), mac.size());
}

}  // namespace meshmark::server
