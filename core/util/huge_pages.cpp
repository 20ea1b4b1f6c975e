#include "core/util/huge_pages.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace meshmark {

namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb=1";

std::string thp_mode_text() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

bool wants_huge_page_restart(const char* tunables, const std::string& thp_mode) {
#ifdef __GLIBC__
  return tunables == nullptr && thp_mode.find("[madvise]") != std::string::npos;
#else
  (void)tunables, (void)thp_mode;
  return false;
#endif
}

std::string huge_page_setting() {
  const std::string text = thp_mode_text();
  const auto open = text.find('['), close = text.find(']');
  const std::string mode =
      open < close && close != std::string::npos ? text.substr(open + 1, close - open - 1) : "none";
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  return "transparent huge pages: " + mode + "; GLIBC_TUNABLES=" + (tunables ? tunables : "(unset)");
}

std::string executable_path() {
  std::error_code error;
  const std::filesystem::path path = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string() : path.string();
}

void restart_with_huge_pages(char** argv) {
  if (!wants_huge_page_restart(std::getenv("GLIBC_TUNABLES"), thp_mode_text())) return;
  // The binary's own path, not /proc/self/exe: the process is named after the file executed, and
  // ps, pgrep and the image's check of the daemon's user find it by that name.
  const std::string self = executable_path();
  if (self.empty() || ::setenv("GLIBC_TUNABLES", kTunable, 0) != 0) return;
  ::execv(self.c_str(), argv);
  ::unsetenv("GLIBC_TUNABLES");  // the restart failed (the binary replaced or gone): run as started
}

}  // namespace meshmark
