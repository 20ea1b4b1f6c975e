#include "server/store/blob_store.hpp"

#include <fstream>
#include <iterator>
#include <cerrno>
#include <stdexcept>
#include <system_error>

#include "core/util/atomic_file.hpp"
#include "server/store/storage_error.hpp"

namespace meshmark::server {

LocalBlobStore::LocalBlobStore(std::filesystem::path root) : root_(std::move(root)) {
  std::filesystem::create_directories(root_);
}

void check_blob_key(const std::string& key) {
  if (key.empty() || key.find("..") != std::string::npos || key.front() == '/')
    throw std::invalid_argument("bad blob key '" + key + "'");
}

std::filesystem::path LocalBlobStore::path_of(const std::string& key) const {
  check_blob_key(key);
  return root_ / key;
}

void LocalBlobStore::put(const std::string& key, const std::string& bytes) {
  const auto path = path_of(key);
  try {
    create_directories_durably(path.parent_path());
    write_file_atomically(path, bytes);
  } catch (const std::system_error& e) {  // std::filesystem::filesystem_error is one too
    const bool full = e.code() == std::errc::no_space_on_device || e.code().value() == EDQUOT;
    throw StorageError(std::string("blob ") + key + ": " + e.what(),
                       full ? StorageError::Kind::full : StorageError::Kind::permanent);
  }
}

std::optional<std::string> LocalBlobStore::get(const std::string& key) {
  std::ifstream in(path_of(key), std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void LocalBlobStore::remove_prefix(const std::string& prefix) {
  std::error_code ec;
  std::filesystem::remove_all(path_of(prefix), ec);
}

void LocalBlobStore::list(const std::string& folder, const BlobVisitor& visit) {
  namespace fs = std::filesystem;
  const fs::path top = path_of(folder);
  std::error_code ec;
  if (!fs::is_directory(top, ec)) return;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(top)) {
    if (!e.is_regular_file() || e.path().filename().string().starts_with(kAtomicTemporaryPrefix)) continue;
    const auto modified = std::chrono::file_clock::to_sys(e.last_write_time());
    visit({e.path().lexically_relative(root_).generic_string(), modified});
  }
}

}  // namespace meshmark::server
