#pragma once
// One daemon per data folder: an exclusive lock on DATA/meshmarkd.lock, held for the daemon's
// life (the kernel drops it when the process ends, even by kill -9). Two daemons on one folder
// would run the same recovered jobs twice and race on its files.

#include <filesystem>

namespace meshmark::server {

class DataDirLock {
 public:
  /// Takes the lock; throws std::runtime_error naming the holder's pid when another process has it.
  explicit DataDirLock(const std::filesystem::path& data_dir);
  ~DataDirLock();
  DataDirLock(const DataDirLock&) = delete;
  DataDirLock& operator=(const DataDirLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace meshmark::server
