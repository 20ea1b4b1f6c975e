#include "core/util/process_memory.hpp"

#include <fstream>
#include <string>

namespace meshmark {

std::optional<std::size_t> peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    return static_cast<std::size_t>(std::stoull(line.substr(6))) * 1024;  // reported in kB
  }
  return std::nullopt;
}

bool reset_peak_resident() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return static_cast<bool>(clear);
}

}  // namespace meshmark
