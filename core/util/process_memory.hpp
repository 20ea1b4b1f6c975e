#pragma once
// The process's resident memory, as Linux reports it: the high-water mark and its reset, so a
// benchmark can attribute a peak to each stage it runs.

#include <cstddef>
#include <optional>

namespace meshmark {

/// Peak resident set size (VmHWM) in bytes, or nothing where /proc is unavailable.
std::optional<std::size_t> peak_resident_bytes();

/// Resets the high-water mark to the current resident size (writes 5 to /proc/self/clear_refs);
/// false where the kernel does not allow it.
bool reset_peak_resident();

}  // namespace meshmark
