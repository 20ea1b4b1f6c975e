#pragma once
// Runs the real `meshmark` binary, as a user or a script would, and captures what it prints.

#include <filesystem>
#include <string>

namespace meshmark::test {

struct CliRun {
  int exit_status = -1;
  std::string out;  ///< standard output (standard error is merged when asked)
};

/// Runs `meshmark <arguments>` through the shell; `arguments` is shell text.
/// `environment`: shell assignments put before the command (e.g. "MESHMARK_THREADS=1"). Records
/// go to cli_records_folder() unless `environment` sets MESHMARK_RECORDS, prepared originals to
/// cli_cache_folder() unless it sets MESHMARK_CACHE.
CliRun run_cli(const std::string& arguments, bool merge_stderr = false, const std::string& environment = "");

/// The records folder of the commands this test process runs (removed at exit).
const std::filesystem::path& cli_records_folder();
/// The cache of prepared originals of the commands this test process runs (removed at exit).
const std::filesystem::path& cli_cache_folder();
/// Where `embed` put the record of the copy `copy` with `payload_hex` by default.
std::string record_of(const std::string& copy, const std::string& payload_hex);

}  // namespace meshmark::test
