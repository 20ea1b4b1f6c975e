#!/usr/bin/env bash
# Installs the web console's npm dependencies (console/package-lock.json: three.js, which the
# daemon compiles in, and playwright-core for its browser tests) into console/node_modules, with
# Node.js from Debian when the machine has none. Idempotent: nothing to do when the installed
# tree matches the lock file.
set -euo pipefail
cd "$(dirname "$0")/../console"
stamp=node_modules/.meshmark-lock.sha256
want=$(sha256sum package-lock.json | cut -d' ' -f1)
if [[ -f "$stamp" && "$(cat "$stamp")" == "$want" ]]; then exit 0; fi
if ! command -v npm >/dev/null; then
  SUDO=""; [[ $(id -u) -ne 0 ]] && SUDO=sudo
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends nodejs npm
fi
npm ci --no-audit --no-fund --loglevel=error >&2
echo "$want" >"$stamp"
