#!/usr/bin/env bash
# Starts meshmarkd with its embedded defaults (listen 127.0.0.1:8080, data in ./meshmark-data,
# one worker per core); flags and MESHMARK_* variables override them. The Docker image, the
# README's run command and the integration tests all start the daemon through this script.
#   MESHMARK_DAEMON  the binary (default: meshmarkd on PATH, else build/server/meshmarkd)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
daemon="${MESHMARK_DAEMON:-}"
if [[ -z "$daemon" ]]; then
  if command -v meshmarkd >/dev/null 2>&1; then daemon="$(command -v meshmarkd)"
  else daemon="$here/../build/server/meshmarkd"; fi
fi
exec "$daemon" "$@"
