#pragma once
// The web console's files, compiled into the daemon (cmake/console_assets.cmake) and served at
// "/" and under "/console/": static, the same for every caller, answered without a store.

#include <string_view>
#include <vector>

namespace meshmark::server {

struct ConsoleFile {
  std::string_view path;  ///< "/" or "/console/…"
  std::string_view media_type;
  std::string_view bytes;
};

const std::vector<ConsoleFile>& console_files();

/// The file served at `path`, or null.
const ConsoleFile* find_console_file(std::string_view path);

/// What the console's responses allow a browser to do: scripts and styles from this origin
/// only (no inline script), WebGL's blob: workers none, no framing by other sites.
inline constexpr const char* kConsoleContentSecurityPolicy =
    "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data: blob:; connect-src 'self'; "
    "base-uri 'none'; form-action 'none'; frame-ancestors 'none'";

}  // namespace meshmark::server
