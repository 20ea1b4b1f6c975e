#include "core/evaluation/host_load.hpp"

#include <algorithm>
#include <fstream>
#include <string>

namespace meshmark {

CpuJiffies cpu_jiffies() {
  std::ifstream stat("/proc/stat");
  std::string cpu;
  stat >> cpu;
  CpuJiffies jiffies;
  double value = 0;
  for (int field = 0; field < 8 && stat >> value; ++field) {  // user … steal; guest time is in user
    jiffies.total += value;
    if (field == 7) jiffies.steal = value;
  }
  return jiffies;
}

double steal_fraction(const CpuJiffies& before, const CpuJiffies& after) {
  const double total = after.total - before.total;
  return total > 0 ? (after.steal - before.steal) / total : 0.0;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  if (n == 0) return 0.0;
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace meshmark
