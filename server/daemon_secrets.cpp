#include "server/daemon_secrets.hpp"

#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <fstream>
#include <set>
#include <stdexcept>

#include "core/util/keyed_random.hpp"
#include "server/secrets.hpp"

namespace meshmark::server {

namespace {

// A secret file the operator made: it must exist (a cluster's key is made once, not per node).
std::string read_configured_secret(const std::filesystem::path& file, const char* what) {
  std::ifstream in(file);
  std::string content;
  if (!in || !std::getline(in, content) || content.empty())
    throw std::runtime_error("cannot read the " + std::string(what) + " from " + file.string() +
                             " (a configured secret file must exist and hold the secret on its first line)");
  struct stat info {};
  if (::stat(file.c_str(), &info) == 0 && (info.st_mode & 077) != 0)
    spdlog::warn("{} is readable by other users (mode {:o}); only the daemon's user should read it", file.string(),
                 info.st_mode & 0777);
  return content;
}

void require_strong(const std::string& secret, std::size_t min_length, const std::string& what) {
  const std::size_t distinct = std::set<char>(secret.begin(), secret.end()).size();
  if (secret.size() < min_length || distinct < kMinAdminTokenDistinct)
    throw std::runtime_error(what + " must be at least " + std::to_string(min_length) + " characters, " +
                             std::to_string(kMinAdminTokenDistinct) + " of them different (it has " +
                             std::to_string(secret.size()) + ", " + std::to_string(distinct) +
                             " different); generate one, e.g. openssl rand -hex 32");
}

std::string master_key(const DaemonConfig& config) {
  if (!config.master_key_file.empty()) {
    std::string key = read_configured_secret(config.master_key_file, "master key");
    require_strong(key, kMinMasterKeyLength, "the master key in " + config.master_key_file.string());
    spdlog::info("master key: read from {}", config.master_key_file.string());
    return key;
  }
  bool created = false;
  const auto path = config.data_dir / "master.key";
  std::string key = load_or_create_secret(path, 32, created);
  if (created) spdlog::info("master key: generated into {} (mode 0600); back it up with the data", path.string());
  return key;
}

std::string admin_token(const DaemonConfig& config) {
  if (!config.admin_token.empty()) {
    spdlog::info("admin token: taken from MESHMARK_ADMIN_TOKEN");
    return config.admin_token;
  }
  if (!config.admin_token_file.empty()) {
    std::string token = read_configured_secret(config.admin_token_file, "admin token");
    require_strong(token, kMinAdminTokenLength, "the admin token in " + config.admin_token_file.string());
    spdlog::info("admin token: read from {}", config.admin_token_file.string());
    return token;
  }
  bool created = false;
  const auto path = config.data_dir / "admin-token";
  std::string token = load_or_create_secret(path, 32, created);
  if (token.size() < kMinAdminTokenLength)
    throw std::runtime_error(path.string() + " holds a token shorter than " + std::to_string(kMinAdminTokenLength) +
                             " characters; write a longer one or delete the file to have one generated");
  spdlog::info("admin token: {} {} (mode 0600)", created ? "generated into" : "read from", path.string());
  return token;
}

}  // namespace

DaemonSecrets load_secrets(const DaemonConfig& config) { return {master_key(config), admin_token(config)}; }

std::string master_key_fingerprint(const std::string& master_key) {
  const auto mac = hmac_sha256(master_key, "meshmark master key fingerprint");
  return to_hex(mac.data(), 16);
}

void check_master_key(Store& store, const std::string& master_key) {
  const std::string ours = master_key_fingerprint(master_key);
  const std::string stored = store.record_master_key_fingerprint(ours);
  if (stored != ours)
    throw std::runtime_error(
        "this store's copies were marked under another master key (fingerprint " + stored + "; this daemon's is " +
        ours +
        "): a copy marked here could not be traced by the other daemons, nor theirs here. Give every daemon "
        "on one store the same master key (--master-key-file)");
  spdlog::info("master key fingerprint {}", ours);
}

}  // namespace meshmark::server
