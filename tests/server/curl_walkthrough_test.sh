#!/usr/bin/env bash
# Runs client/curl/walkthrough.sh, exactly as the README prints it, against a real daemon on a
# free loopback port, and checks that the detection names the recipient of the copy.
# Usage: curl_walkthrough_test.sh START_SCRIPT MESHMARKD CURL_DIR MESH [MESHMARK_CLI]
#   MESH  a mesh file, or example:SHAPE for a shape `meshmark example` writes (needs MESHMARK_CLI)
set -euo pipefail
start="$1"; daemon="$2"; curl_dir="$3"; mesh="$4"; cli="${5:-}"
work=$(mktemp -d); trap 'kill $pid 2>/dev/null; wait $pid 2>/dev/null; rm -rf "$work"' EXIT
if [[ "$mesh" == example:* ]]; then
  "$cli" example "${mesh#example:}" "$work/${mesh#example:}.obj"
  mesh="$work/${mesh#example:}.obj"
fi
MESHMARK_DAEMON="$daemon" "$start" --listen 127.0.0.1:0 --data "$work/data" >"$work/out" 2>"$work/log" &
pid=$!
for _ in $(seq 100); do grep -q "listening on" "$work/out" && break; sleep 0.1; done
server=$(grep -o "http://[0-9.:]*" "$work/out")
export MESHMARK_SERVER="$server" MESHMARK_ADMIN_TOKEN=$(cat "$work/data/admin-token")
output=$("$curl_dir/walkthrough.sh" "$mesh" "$work")
echo "$output"
last=$(tail -1 <<<"$output")
grep -q '"state":"succeeded"' <<<"$last"
grep -q '"detected":true' <<<"$last"
grep -q '"match":{[^}]*"recipient":"reseller-42"' <<<"$last"
grep -q '"requested_by":"Ana \\"A.\\" Licensing"' <<<"$output"  # who asked, quotes and all
echo "walkthrough: detection names reseller-42"
