#pragma once
// Where this build put the programs the tests start, and the checkout they come from. These paths
// differ from one clone to the next, so they live in build_paths.cpp alone: every other test
// source then compiles to the same object in any folder, and ccache serves a fresh clone.

namespace meshmark::test {

/// The meshmark CLI this build made.
const char* cli_program();

/// The meshmarkd daemon this build made.
const char* daemon_program();

/// deploy/start-daemon.sh in the checkout.
const char* start_script();

/// The checkout's root folder.
const char* source_dir();

/// $MESHMARK_SHARED when the build was configured (else ../shared beside the checkout).
const char* configured_shared_root();

}  // namespace meshmark::test
