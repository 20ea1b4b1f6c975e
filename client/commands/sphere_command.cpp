#include "client/commands/commands.hpp"

namespace meshmark::cli {
void register_sphere(CLI::App&, Action&) {}
}  // namespace meshmark::cli
