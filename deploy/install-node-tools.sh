#!/usr/bin/env bash
# Installs the npm tools the tests use — the Khronos glTF validator (gltf-validator), which every
# marked glTF must pass whenever its original does, and s3rver, the S3-compatible server the blob
# store tests run against (deploy/s3-test-server.sh) — into the cache folder (deploy/cache-dir.sh),
# outside the clone, and Node.js from Debian when the machine has none. Idempotent. Prints the
# node_modules folder the tests read (MESHMARK_NODE_MODULES) on its last line.
set -euo pipefail
cd "$(dirname "$0")/.."
validator_version=2.0.0-dev.3.10
s3rver_version=3.7.1
prefix="$(deploy/cache-dir.sh)/node"
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  SUDO=""; [[ $(id -u) -ne 0 ]] && SUDO=sudo
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends nodejs npm
fi
installed="$prefix/node_modules/gltf-validator/package.json"
if ! grep -q "\"version\": \"$validator_version\"" "$installed" 2>/dev/null; then
  npm install --no-audit --no-fund --loglevel=error --prefix "$prefix" "gltf-validator@$validator_version" >&2
fi
if ! grep -q "\"version\": \"$s3rver_version\"" "$prefix/node_modules/s3rver/package.json" 2>/dev/null; then
  npm install --no-audit --no-fund --loglevel=error --prefix "$prefix" "s3rver@$s3rver_version" >&2
fi
echo "$prefix/node_modules"
