#include "tests/client/cli_runner.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <stdexcept>

#include "client/commands/copy_record_files.hpp"
#include "tests/build_paths.hpp"
#include "tests/procedural_meshes.hpp"

namespace meshmark::test {

const std::filesystem::path& cli_records_folder() {
  static const std::filesystem::path folder = process_temp_folder("meshmark-records");
  return folder;
}

const std::filesystem::path& cli_cache_folder() {
  static const std::filesystem::path folder = process_temp_folder("meshmark-cache");
  return folder;
}

std::string record_of(const std::string& copy, const std::string& payload_hex) {
  return cli::record_path_in(cli_records_folder(), copy, payload_hex).string();
}

CliRun run_cli(const std::string& arguments, bool merge_stderr, const std::string& environment) {
  const std::string records = environment.find("MESHMARK_RECORDS=") == std::string::npos
                                  ? "MESHMARK_RECORDS='" + cli_records_folder().string() + "' "
                                  : "";
  // Prepared originals cached in this test's own folder, never the user's.
  const std::string cache = environment.find("MESHMARK_CACHE=") == std::string::npos
                                ? "MESHMARK_CACHE='" + cli_cache_folder().string() + "' "
                                : "";
  const std::string command = records + cache + (environment.empty() ? "" : environment + " ") +
                              std::string(cli_program()) + " " + arguments + (merge_stderr ? " 2>&1" : " 2>/dev/null");
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  CliRun run;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace meshmark::test
