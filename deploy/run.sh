#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine and runs the daemon with embedded defaults:
# http://127.0.0.1:8080, data in ./meshmark-data (the admin token is generated into
# ./meshmark-data/admin-token on first start). Stop it with Ctrl-C (it drains cleanly).
set -euo pipefail
cd "$(dirname "$0")/.."
deploy/install-deps.sh
deploy/build.sh -DBUILD_TESTING=OFF
exec deploy/start-daemon.sh "$@"
