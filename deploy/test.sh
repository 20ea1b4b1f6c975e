#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine and runs the whole test suite.
# The shared meshes are read from ../shared/meshes (override with MESHMARK_MESHES).
set -euo pipefail
cd "$(dirname "$0")/.."
deploy/install-deps.sh
deploy/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 900
