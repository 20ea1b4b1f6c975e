#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine and runs the whole test suite: the release build
# and its tests (the robustness gate included), then the sanitizer build, its focused tests and a
# short fuzzing run of every target (deploy/sanitize.sh; FUZZ_SECONDS per target, default 30).
# The shared meshes are read from ../shared/meshes (override with MESHMARK_MESHES).
set -euo pipefail
cd "$(dirname "$0")/.."
deploy/install-deps.sh
# Tests are asked for explicitly: a build folder configured by deploy/run.sh has them off.
deploy/build.sh -DBUILD_TESTING=ON
jobs=$(deploy/cpus.sh)
export MESHMARK_THREADS="${MESHMARK_THREADS:-$jobs}"  # the CLI's parallel loops in the tests: the cores we have
(cd build && ctest --output-on-failure --no-tests=error -j"$jobs" --timeout 900)
deploy/sanitize.sh
