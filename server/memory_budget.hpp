#pragma once
// The daemon's memory ceiling, shared by everything that holds a mesh: an upload's parse, a job,
// a prepared model kept in the cache. Each asks for what it will hold before it starts and is
// refused (a request: 503), waits (a job) or makes room (the cache) when the rest of the ceiling
// is taken, so that any number of large requests at once stay under the ceiling.

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>

#include "core/util/job_control.hpp"

namespace meshmark::server {

class MemoryBudget;

/// Bytes held against a MemoryBudget until destroyed (or moved from).
class MemoryReservation {
 public:
  MemoryReservation() = default;
  MemoryReservation(MemoryReservation&& other) noexcept;
  MemoryReservation& operator=(MemoryReservation&& other) noexcept;
  MemoryReservation(const MemoryReservation&) = delete;
  MemoryReservation& operator=(const MemoryReservation&) = delete;
  ~MemoryReservation();

  std::size_t bytes() const { return bytes_; }

 private:
  friend class MemoryBudget;
  MemoryReservation(MemoryBudget& budget, std::size_t bytes) : budget_(&budget), bytes_(bytes) {}
  void release();

  MemoryBudget* budget_ = nullptr;
  std::size_t bytes_ = 0;
};

class MemoryBudget {
 public:
  explicit MemoryBudget(std::size_t ceiling_bytes) : ceiling_(ceiling_bytes) {}
  MemoryBudget(const MemoryBudget&) = delete;
  MemoryBudget& operator=(const MemoryBudget&) = delete;

  std::size_t ceiling() const { return ceiling_; }
  std::size_t reserved() const;
  std::size_t available() const { return ceiling_ - reserved(); }
  /// Now or never: nothing when `bytes` do not fit beside what is reserved now (or at all).
  std::optional<MemoryReservation> try_reserve(std::size_t bytes);
  /// Waits until `bytes` fit; more than the ceiling waits for all of it (the holder runs alone).
  /// Throws what control.poll() throws while waiting.
  MemoryReservation reserve(std::size_t bytes, const JobControl& control);

 private:
  friend class MemoryReservation;
  void release(std::size_t bytes);

  const std::size_t ceiling_;
  mutable std::mutex mutex_;
  std::condition_variable freed_;
  std::size_t reserved_ = 0;
};

// What holding a mesh costs, measured on the daemon's own runs (docs/performance.md), with room.
/// An upload as read into memory: its bytes twice (the body and what is written from it) and
/// each vertex of the document, its surface, validation and stored copy (~520 B measured).
inline constexpr std::size_t kUploadBytesPerVertex = 640;
/// A body is first read as if it held this many bytes per vertex: the densest common uncompressed
/// encoding (float positions, 16-bit indices) stores a vertex and its two faces in 24.
inline constexpr std::size_t kBodyBytesPerVertex = 24;
/// A job's working memory per vertex of the model and the suspect (embed peaks ~1.8 KB measured).
inline constexpr std::size_t kJobBytesPerVertex = 2048;
/// A prepared model kept in the cache, per vertex (~550 B measured).
inline constexpr std::size_t kPreparedBytesPerVertex = 640;

inline std::size_t upload_memory_cost(std::size_t body_bytes, std::size_t vertices) {
  return 2 * body_bytes + kUploadBytesPerVertex * vertices;
}

/// The memory this process may use: the cgroup's limit where one is set (a container), else the
/// machine's physical memory.
std::size_t available_memory_bytes();

}  // namespace meshmark::server
