#include "server/http/console_files.hpp"

namespace meshmark::server {

const ConsoleFile* find_console_file(std::string_view path) {
  for (const ConsoleFile& f : console_files())
    if (f.path == path) return &f;
  return nullptr;
}

}  // namespace meshmark::server
