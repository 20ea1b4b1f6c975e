#pragma once
// Runs the real `meshmark` binary, as a user or a script would, and captures what it prints.

#include <string>

namespace meshmark::test {

struct CliRun {
  int exit_status = -1;
  std::string out;  ///< standard output (standard error is merged when asked)
};

/// Runs `meshmark <arguments>` through the shell; `arguments` is shell text.
/// `environment`: shell assignments put before the command (e.g. "MESHMARK_THREADS=1").
CliRun run_cli(const std::string& arguments, bool merge_stderr = false, const std::string& environment = "");

}  // namespace meshmark::test
