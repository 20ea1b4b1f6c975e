#include "core/util/parallel_for.hpp"

namespace meshmark {

int hardware_threads() {
  const unsigned hardware = std::thread::hardware_concurrency();
  return static_cast<int>(std::clamp(hardware, 1u, 8u));
}

int resolve_threads(int requested) { return requested > 0 ? requested : hardware_threads(); }

}  // namespace meshmark
