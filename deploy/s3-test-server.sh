#!/usr/bin/env bash
# Starts the S3-compatible server the blob store tests run against — s3rver from npm
# (deploy/install-node-tools.sh), on a free loopback port, its bucket "meshmark-test" made at
# start — in the background, its data in FOLDER. Prints "ENDPOINT PID" once it listens.
# Usage: deploy/s3-test-server.sh FOLDER
set -euo pipefail
cd "$(dirname "$0")/.."
folder=${1:?usage: deploy/s3-test-server.sh FOLDER}
modules="${MESHMARK_NODE_MODULES:-$(deploy/cache-dir.sh)/node/node_modules}"
mkdir -p "$folder/data"
node "$modules/s3rver/bin/s3rver.js" -d "$folder/data" -a 127.0.0.1 -p 0 --silent \
  --configure-bucket meshmark-test > "$folder/log" 2>&1 &
pid=$!
for _ in $(seq 100); do
  port=$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$folder/log")
  if [[ -n "$port" ]]; then
    echo "http://127.0.0.1:$port $pid"
    exit 0
  fi
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
echo "s3-test-server: s3rver did not start:" >&2
cat "$folder/log" >&2
kill "$pid" 2>/dev/null || true
exit 1
