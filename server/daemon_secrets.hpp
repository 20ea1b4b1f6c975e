#pragma once
// The secrets every daemon on one store must share: the master key (every owner's watermark key
// derives from it) and the admin token. Alone, a daemon generates both into its data folder on
// first start; in a cluster they come from configuration (files, e.g. Docker secrets, or the
// environment), and the store keeps the master key's fingerprint so that a daemon given another
// key refuses to start instead of marking copies no peer could trace.

#include <string>

#include "server/config.hpp"
#include "server/store/store.hpp"

namespace meshmark::server {

struct DaemonSecrets {
  std::string master_key;
  std::string admin_token;
};

/// A configured secret must be at least this long, with this many different characters.
inline constexpr std::size_t kMinMasterKeyLength = 32;

/// Reads (or, with nothing configured, generates into the data folder) both secrets. Throws
/// std::runtime_error saying what is wrong.
DaemonSecrets load_secrets(const DaemonConfig& config);

/// What may be shown and stored of a master key: 128 bits of an HMAC of it, hex.
std::string master_key_fingerprint(const std::string& master_key);

/// Records the key's fingerprint in a store that has none; throws std::runtime_error when the
/// store's copies were marked under another key.
void check_master_key(Store& store, const std::string& master_key);

}  // namespace meshmark::server
