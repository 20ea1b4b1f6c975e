#pragma once
// Counters for /metrics, rendered in the Prometheus text format.

#include <map>
#include <mutex>
#include <string>
#include <tuple>

namespace meshmark::server {

class Metrics {
 public:
  void count_request(const std::string& method, const std::string& route, int status);
  void observe_stage(const std::string& kind, const std::string& stage, double seconds);
  void observe_job(const std::string& kind, const std::string& state, double seconds);

  /// What the daemon holds now: the live queue and the memory budget.
  struct Live {
    std::size_t queued = 0, running = 0, queue_capacity = 0;
    std::size_t memory_reserved = 0, memory_ceiling = 0;  ///< bytes
    std::string instance;  ///< which daemon answers (its instance id): the others share the store
  };
  /// `jobs`: (kind, state) → count from the store, the same from every daemon on it; the rest is
  /// this daemon's.
  std::string render(const std::map<std::pair<std::string, std::string>, long long>& jobs, const Live& live) const;

 private:
  struct Sum {
    double seconds = 0;
    long long count = 0;
  };
  // A Prometheus summary labelled by kind and `second_label`.
  static void append_summary(std::string& out, const char* name, const char* help, const char* second_label,
                             const std::map<std::pair<std::string, std::string>, Sum>& sums);

  mutable std::mutex mutex_;
  std::map<std::tuple<std::string, std::string, int>, long long> requests_;
  std::map<std::pair<std::string, std::string>, Sum> stages_;
  std::map<std::pair<std::string, std::string>, Sum> jobs_;
};

}  // namespace meshmark::server
