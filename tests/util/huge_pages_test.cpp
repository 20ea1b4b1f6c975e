// When a command restarts itself to give glibc's malloc transparent huge pages.

#include "core/util/huge_pages.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace meshmark
