#include "core/util/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

namespace meshmark {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const char* what) {
  throw std::system_error(errno, std::generic_category(), path.string() + ": " + what);
}

void write_all(int fd, std::string_view bytes, const std::filesystem::path& path) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(path, "cannot write");
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

// Files from this size on are written past the page cache (O_DIRECT): they are fsynced at once
// anyway, and on a virtual machine taking fresh page-cache memory for a few megabytes cost up to
// 30 ms where the direct write took 4.
constexpr std::size_t kDirectFrom = std::size_t{1} << 20;
constexpr std::size_t kBlock = 4096;  // the alignment direct writes ask of buffers, offsets and lengths

// Writes `bytes` to `fd` (opened with O_DIRECT) through an aligned buffer, the last block padded
// with zeros and cut off after. False when the filesystem refuses direct writes (EINVAL).
bool write_all_direct(int fd, std::string_view bytes, const std::filesystem::path& path) {
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  const std::unique_ptr<char, decltype(&std::free)> buffer(static_cast<char*>(std::aligned_alloc(kBlock, kChunk)),
                                                           &std::free);
  if (!buffer) return false;
  for (std::size_t offset = 0; offset < bytes.size(); offset += kChunk) {
    const std::size_t size = std::min(kChunk, bytes.size() - offset);
    const std::size_t padded = (size + kBlock - 1) / kBlock * kBlock;
    std::memcpy(buffer.get(), bytes.data() + offset, size);
    std::memset(buffer.get() + size, 0, padded - size);
    for (std::size_t done = 0; done < padded;) {
      const ssize_t n = ::pwrite(fd, buffer.get() + done, padded - done, static_cast<off_t>(offset + done));
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && errno == EINVAL) return false;
      if (n <= 0) fail(path, "cannot write");
      done += static_cast<std::size_t>(n);
    }
  }
  if (::ftruncate(fd, static_cast<off_t>(bytes.size())) != 0) fail(path, "cannot write");
  return true;
}

// The temporary file, written whole: directly when it is large and the filesystem allows.
int write_temporary(const std::filesystem::path& tmp, std::string_view bytes) {
  constexpr int kFlags = O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC;
  if (bytes.size() >= kDirectFrom) {
    const int fd = ::open(tmp.c_str(), kFlags | O_DIRECT, 0644);
    if (fd >= 0) {
      try {
        if (write_all_direct(fd, bytes, tmp)) return fd;
      } catch (...) {
        ::close(fd);
        throw;
      }
      ::close(fd);
    }
  }
  const int fd = ::open(tmp.c_str(), kFlags, 0644);
  if (fd < 0) fail(tmp, "cannot create");
  try {
    write_all(fd, bytes, tmp);
  } catch (...) {
    ::close(fd);
    throw;
  }
  return fd;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  const std::filesystem::path tmp = dir / (std::string(kAtomicTemporaryPrefix) + path.filename().string() + "-" +
                                           std::to_string(::getpid()) + "-" + std::to_string(counter++));
  int fd = -1;
  try {
    fd = write_temporary(tmp, bytes);
    if (::fsync(fd) != 0) fail(tmp, "cannot fsync");
  } catch (...) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  ::close(fd);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    fail(path, "cannot rename into place");
  }
  fsync_directory(dir);
}

void fsync_directory(const std::filesystem::path& dir) {
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

void create_directories_durably(const std::filesystem::path& dir) {
  if (dir.empty() || std::filesystem::is_directory(dir)) return;
  create_directories_durably(dir.parent_path());
  std::filesystem::create_directory(dir);
  fsync_directory(dir.has_parent_path() ? dir.parent_path() : ".");  // the new entry itself
}

}  // namespace meshmark
