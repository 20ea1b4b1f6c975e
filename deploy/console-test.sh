#!/usr/bin/env bash
# The web console's browser tests (console/tests/console.test.mjs): Debian's chromium, headless,
# driven by playwright-core, against a daemon from the release build. Screenshots of every view
# are written to build/console-screenshots/ for review (not committed).
# Usage: deploy/console-test.sh   (after deploy/build.sh; deploy/test.sh runs it as a stage)
set -euo pipefail
cd "$(dirname "$0")/.."
deploy/install-deps.sh browser
deploy/build-console.sh
shared="${MESHMARK_SHARED:-$(cd .. && pwd)/shared}"
mesh="$shared/meshes/bunny.obj"
if [[ ! -f "$mesh" ]]; then
  # Without the real meshes: the example shape the README starts from.
  mesh="$(mktemp -d)/creature.obj"
  build/client/meshmark example creature-large "$mesh" >/dev/null
  echo "console tests: bunny.obj absent; on the example creature instead"
fi
MESHMARK_DAEMON="$PWD/build/server/meshmarkd" MESHMARK_CLI="$PWD/build/client/meshmark" MESHMARK_TEST_MESH="$mesh" \
  SCREENSHOTS="$PWD/build/console-screenshots" node console/tests/console.test.mjs
