#!/usr/bin/env bash
# Load test of meshmarkd on loopback with wrk: request throughput of GET /livez, then job
# throughput of embeds on a prepared model (the bunny) while wrk keeps the queue full.
# Usage: tests/load/load_test.sh [SECONDS]        (from a built tree: build/server/meshmarkd)
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds="${1:-20}"
command -v wrk >/dev/null || deploy/install-deps.sh --load-tools
daemon=build/server/meshmarkd
mesh="${MESHMARK_SHARED:-../shared}/meshes/bunny.obj"
work=$(mktemp -d); trap 'kill $pid 2>/dev/null; wait $pid 2>/dev/null; rm -rf "$work"' EXIT

MESHMARK_DAEMON="$daemon" deploy/start-daemon.sh --listen 127.0.0.1:0 --data "$work/data" --log-level warn \
  >"$work/out" 2>"$work/log" &
pid=$!
for _ in $(seq 100); do grep -q "listening on" "$work/out" && break; sleep 0.1; done
server=$(grep -o "http://[0-9.:]*" "$work/out")
. client/curl/common.sh
export MESHMARK_SERVER="$server" MESHMARK_ADMIN_TOKEN=$(cat "$work/data/admin-token")
export TOKEN=$(client/curl/create-owner.sh load | json_field api_key)
export MESHMARK_TOKEN="$TOKEN"
model=$(client/curl/upload-model.sh "$mesh")
export MODEL=$(json_field id <<<"$model")
client/curl/wait-job.sh "$(json_field job_id <<<"$model")" >/dev/null

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "daemon: $(grep -o '([^)]*)' "$work/out")"
echo
echo "== GET /livez: wrk -t2 -c32 -d${seconds}s"
wrk -t2 -c32 -d"${seconds}s" --latency "$server/livez" | grep -E "Requests/sec|Latency|50%|99%"

echo
echo "== POST /v1/models/{id}/embed on the prepared bunny: wrk -t1 -c4 -d${seconds}s"
metric() { curl -sS "$server/metrics" | awk -v k="$1" '$1 == k { print $2 }'; }
start=$(date +%s.%N)
wrk -t1 -c4 -d"${seconds}s" -s tests/load/embed.lua "$server" | grep -E "embed requests|Requests/sec"
while [[ "$(metric meshmark_queue_depth)" != "0" || "$(metric meshmark_jobs_running)" != "0" ]]; do sleep 0.2; done
end=$(date +%s.%N)
done_jobs=$(metric 'meshmark_jobs{kind="embed",state="succeeded"}')
failed_jobs=$(metric 'meshmark_jobs{kind="embed",state="failed"}')
sum=$(metric 'meshmark_job_seconds_sum{kind="embed",state="succeeded"}')
awk -v n="$done_jobs" -v f="${failed_jobs:-0}" -v s="$start" -v e="$end" -v sum="$sum" 'BEGIN {
  printf "embed jobs: %d succeeded, %d failed in %.1f s (until the queue drained): %.1f jobs/s; mean job run time %.0f ms\n",
         n, f, e - s, n / (e - s), 1000 * sum / n }'
