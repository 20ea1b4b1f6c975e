#pragma once
// What a benchmark needs to say about its runs: their median, and how much of the machine the
// hypervisor took meanwhile (CPU steal), since on a shared VM the same work takes longer.

#include <vector>

namespace meshmark {

/// Jiffies of all CPUs since boot, from /proc/stat (zeros where it cannot be read).
struct CpuJiffies {
  double total = 0;
  double steal = 0;
};
CpuJiffies cpu_jiffies();

/// The share of the machine's time stolen between two readings (0 when no time passed).
double steal_fraction(const CpuJiffies& before, const CpuJiffies& after);

/// The median (the mean of the two middle values for an even count; 0 for none).
double median(std::vector<double> values);

}  // namespace meshmark
