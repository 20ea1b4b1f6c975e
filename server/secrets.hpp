#pragma once
// Identifiers, tokens and the keys that must never be stored in the clear.
//
// API keys are shown once and stored only as SHA-256 hashes (they are 256-bit random tokens, so
// a fast hash is enough). Owners' watermark keys cannot be hashed (detection needs them): they are
// derived as HMAC-SHA256(master key, owner id), the master key living in a 0600 file.

#include <filesystem>
#include <string>

namespace meshmark::server {

/// `bytes` random bytes from the system's CSPRNG, as lower-case hex.
std::string random_hex(std::size_t bytes);

/// A new identifier: prefix + 20 random hex digits (80 bits), e.g. "mdl_3f2a…".
std::string new_id(const std::string& prefix);

/// A new API key ("mmk_" + 64 hex digits) and the hash to store.
std::string new_api_key();
std::string hash_api_key(const std::string& key);

/// Equal strings, in time independent of where they differ.
bool constant_time_equal(const std::string& a, const std::string& b);

/// The content of a secret file, created with `bytes` random bytes (hex) and mode 0600 if it
/// does not exist. Throws std::runtime_error if it exists with group or other permissions.
std::string load_or_create_secret(const std::filesystem::path& file, std::size_t bytes, bool& created);

/// The watermark key of an owner: HMAC-SHA256(master, "meshmark owner key/" + owner id), hex.
std::string owner_watermark_key(const std::string& master_key, const std::string& owner_id);

}  // namespace meshmark::server
