#!/usr/bin/env bash
# Lints deploy/Dockerfile without a Docker engine: dockerfile-utils (the validator behind the VS
# Code Docker extension; checks instructions, arguments, flags, durations and ports) from npm.
# hadolint is not packaged for Debian and its binary is not reachable from here.
# Needs node and npm (apt-get install npm).
set -euo pipefail
cd "$(dirname "$0")/.."
tools=$(mktemp -d); trap 'rm -rf "$tools"' EXIT
npm install --silent --prefix "$tools" dockerfile-utils@0.16.3 >/dev/null
"$tools/node_modules/.bin/dockerfile-utils" lint deploy/Dockerfile
echo "deploy/Dockerfile: no problems found by dockerfile-utils 0.16.3"
