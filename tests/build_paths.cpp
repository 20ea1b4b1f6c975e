#include "tests/build_paths.hpp"

// The macros come from tests/CMakeLists.txt, set on this file only.
namespace meshmark::test {

const char* cli_program() { return MESHMARK_CLI; }
const char* daemon_program() { return MESHMARK_DAEMON; }
const char* start_script() { return MESHMARK_START_SCRIPT; }
const char* source_dir() { return MESHMARK_SOURCE_DIR; }
const char* configured_shared_root() { return MESHMARK_SHARED; }

}  // namespace meshmark::test
