#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine and runs meshmark. Until the daemon lands this
# is a demo of the command-line tool on a shared mesh.
set -euo pipefail
cd "$(dirname "$0")/.."
deploy/install-deps.sh
deploy/build.sh
MESHES="${MESHMARK_MESHES:-../shared/meshes}"
build/client/meshmark info "$MESHES/bunny.obj" || true
build/client/meshmark sphere "$MESHES/bunny.obj"
