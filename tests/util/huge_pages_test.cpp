// When a command restarts itself to give glibc's malloc transparent huge pages.

#include "core/util/huge_pages.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <filesystem>

namespace meshmark {
namespace {

#ifdef __GLIBC__
// Only where the kernel gives huge pages to memory that asks, and never over a user's own
// tunables: a restarted process finds them set, so it cannot restart twice.
TEST(HugePages, ARestartIsWantedOnlyWhereMemoryMustAskAndNoTunableIsSet) {
  EXPECT_TRUE(wants_huge_page_restart(nullptr, "always [madvise] never\n"));
  EXPECT_FALSE(wants_huge_page_restart(nullptr, "[always] madvise never\n"));
  EXPECT_FALSE(wants_huge_page_restart(nullptr, "always madvise [never]\n"));
  EXPECT_FALSE(wants_huge_page_restart(nullptr, ""));  // no THP, or no /sys
  EXPECT_FALSE(wants_huge_page_restart("glibc.malloc.hugetlb=1", "always [madvise] never\n"));
  EXPECT_FALSE(wants_huge_page_restart("glibc.malloc.arena_max=2", "always [madvise] never\n"));
}
#endif

// A restart executes the binary by its own name: executed as /proc/self/exe, a process is named
// "exe", and ps, pgrep and the image's check of the daemon's user no longer find it.
TEST(HugePages, TheRestartExecutesTheBinaryByItsOwnName) {
  const std::filesystem::path self = executable_path();
  ASSERT_FALSE(self.empty());
  EXPECT_TRUE(self.is_absolute());
  EXPECT_EQ(self.filename().string(), program_invocation_short_name);
}

}  // namespace
}  // namespace meshmark
