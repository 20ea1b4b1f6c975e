#include "core/util/parallel_for.hpp"

#include <cstdlib>
#include <string>

namespace meshmark {

int parallel_threads() {
  static const int threads = [] {
    if (const char* env = std::getenv("MESHMARK_THREADS")) {
      try {
        const int n = std::stoi(env);
        if (n >= 1 && n <= 64) return n;
      } catch (const std::exception&) {
      }
    }
    const unsigned hardware = std::thread::hardware_concurrency();
    return static_cast<int>(std::clamp(hardware, 1u, 8u));
  }();
  return threads;
}

}  // namespace meshmark
