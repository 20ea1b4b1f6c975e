#pragma once
// Transparent huge pages for glibc's malloc. Where the kernel gives them only to memory that asks
// (THP mode "madvise", Debian's default), every large array a pipeline allocates is faulted in 4 KiB
// at a time: at 557k vertices the page faults were an eighth of an embed's time on a virtual
// machine, where each one traps to the hypervisor. glibc asks for huge pages when its tunable
// glibc.malloc.hugetlb=1 is set, which it reads only when a process starts: meshmark and
// meshmarkd restart themselves once with it set (about 25 ms of dynamic loading).

#include <string>

namespace meshmark {

/// Whether a process should restart with the tunable: glibc is the C library, the kernel's THP
/// mode (the text of /sys/kernel/mm/transparent_hugepage/enabled) is "madvise", and
/// `tunables` (GLIBC_TUNABLES, or null) is unset — a user's own setting is left alone, and a
/// restarted process finds it set.
bool wants_huge_page_restart(const char* tunables, const std::string& thp_mode);

/// The running binary's path (where /proc/self/exe points), or "" where it cannot be read.
std::string executable_path();

/// Re-executes this program (executable_path(), the same arguments) with GLIBC_TUNABLES set to
/// glibc.malloc.hugetlb=1 when wants_huge_page_restart says so; returns when it does not, or when
/// the restart fails (the process then runs as it is).
void restart_with_huge_pages(char** argv);

/// What a benchmark's figures depend on here: the kernel's THP mode (the bracketed word) and
/// GLIBC_TUNABLES, e.g. "transparent huge pages: madvise; GLIBC_TUNABLES=glibc.malloc.hugetlb=1".
std::string huge_page_setting();

}  // namespace meshmark
