#include "server/memory_budget.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

namespace meshmark::server {

MemoryReservation::MemoryReservation(MemoryReservation&& other) noexcept
    : budget_(std::exchange(other.budget_, nullptr)), bytes_(std::exchange(other.bytes_, 0)) {}

MemoryReservation& MemoryReservation::operator=(MemoryReservation&& other) noexcept {
  if (this != &other) {
    release();
    budget_ = std::exchange(other.budget_, nullptr);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

MemoryReservation::~MemoryReservation() { release(); }

void MemoryReservation::release() {
  if (budget_) budget_->release(bytes_);
  budget_ = nullptr;
  bytes_ = 0;
}

std::size_t MemoryBudget::reserved() const {
  std::lock_guard lock(mutex_);
  return reserved_;
}

std::optional<MemoryReservation> MemoryBudget::try_reserve(std::size_t bytes) {
  std::lock_guard lock(mutex_);
  if (bytes > ceiling_ - reserved_) return std::nullopt;
  reserved_ += bytes;
  return MemoryReservation(*this, bytes);
}

MemoryReservation MemoryBudget::reserve(std::size_t bytes, const JobControl& control) {
  bytes = std::min(bytes, ceiling_);
  std::unique_lock lock(mutex_);
  // Woken by every release; the timeout only bounds how late a cancel or the deadline is seen.
  while (bytes > ceiling_ - reserved_) {
    freed_.wait_for(lock, std::chrono::milliseconds(200));
    control.poll();
  }
  reserved_ += bytes;
  return MemoryReservation(*this, bytes);
}

void MemoryBudget::release(std::size_t bytes) {
  {
    std::lock_guard lock(mutex_);
    reserved_ -= bytes;
  }
  freed_.notify_all();
}

namespace {

// cgroup v2's memory.max ("max" when unlimited), else v1's limit (a huge number when unlimited).
std::optional<std::size_t> cgroup_limit() {
  for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    std::string text;
    if (!(in >> text) || text == "max") continue;
    try {
      return static_cast<std::size_t>(std::stoull(text));
    } catch (const std::exception&) {
      continue;
    }
  }
  return std::nullopt;
}

}  // namespace

std::size_t available_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  const std::size_t physical = pages > 0 && page > 0 ? static_cast<std::size_t>(pages) * page : std::size_t{4} << 30;
  const auto limit = cgroup_limit();
  return limit ? std::min(*limit, physical) : physical;
}

}  // namespace meshmark::server
