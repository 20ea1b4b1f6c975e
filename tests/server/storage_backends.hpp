#pragma once
// Every store and blob store backend the contract tests run against: the embedded ones always,
// the shared ones when the test command started their servers (else their tests skip).

#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "server/clock.hpp"
#include "server/store/blob_store.hpp"
#include "server/store/store.hpp"

namespace meshmark::test {

/// A clock that stands still until moved.
class ManualClock : public server::Clock {
 public:
  TimePoint now() const override { return now_; }
  void advance(std::chrono::milliseconds by) { now_ += by; }
  void set(TimePoint t) { now_ = t; }

 private:
  TimePoint now_ = std::chrono::sys_days{std::chrono::year{2026} / 1 / 1};
};

struct StoreBackend {
  std::string name;
  /// The store at `place` (a fresh folder per test); the same place opens the same store again.
  std::function<std::unique_ptr<server::Store>(const std::filesystem::path& place, const server::Clock& clock)> open;
  /// Why it cannot run here (its server was not started), or empty (see BlobBackend).
  std::function<std::string()> absent = [] { return std::string(); };
};
std::vector<StoreBackend> store_backends();

struct BlobBackend {
  std::string name;
  std::function<std::unique_ptr<server::BlobStore>(const std::filesystem::path& place)> open;
  /// Why it cannot run here (its server was not started), or empty. Every backend is listed
  /// either way, so that the tests discovered at build time are the same on every machine.
  std::function<std::string()> absent = [] { return std::string(); };
};
std::vector<BlobBackend> blob_backends();

/// The URI of a database of its own for `place` on the PostgreSQL server the test command started
/// (MESHMARK_TEST_POSTGRES, a URI ending in /postgres), made on first use.
std::string postgres_test_database(const std::filesystem::path& place);

/// For INSTANTIATE_TEST_SUITE_P's names, and gtest's printing of a parameter.
inline std::string backend_name(const StoreBackend& b) { return b.name; }
inline std::string backend_name(const BlobBackend& b) { return b.name; }
inline void PrintTo(const StoreBackend& b, std::ostream* out) { *out << b.name; }
inline void PrintTo(const BlobBackend& b, std::ostream* out) { *out << b.name; }

}  // namespace meshmark::test
