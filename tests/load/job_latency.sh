#!/usr/bin/env bash
# Daemon job latency on a prepared model (the bunny): embed and detect jobs, one at a time and
# two at once (both cores busy, 2 workers). Latency = finished_at − created_at as the daemon
# records them (queueing included); medians of RUNS. Then throughput: BATCH jobs of each kind
# submitted at once, jobs ÷ (last finished_at − first created_at).
# Usage: tests/load/job_latency.sh [RUNS] [BATCH]        (from a built tree)
set -euo pipefail
cd "$(dirname "$0")/../.."
runs="${1:-5}"; batch="${2:-40}"
mesh="${MESHMARK_SHARED:-../shared}/meshes/bunny.obj"
work=$(mktemp -d); trap 'kill $pid 2>/dev/null; wait $pid 2>/dev/null; rm -rf "$work"' EXIT
MESHMARK_DAEMON=build/server/meshmarkd deploy/start-daemon.sh --listen 127.0.0.1:0 --data "$work/data" --workers 2 \
  --log-level warn >"$work/out" 2>"$work/log" &
pid=$!
for _ in $(seq 100); do grep -q "listening on" "$work/out" && break; sleep 0.1; done
. client/curl/common.sh
export MESHMARK_SERVER=$(grep -o "http://[0-9.:]*" "$work/out") MESHMARK_ADMIN_TOKEN=$(cat "$work/data/admin-token")
export MESHMARK_TOKEN=$(client/curl/create-owner.sh latency | json_field api_key)
model=$(client/curl/upload-model.sh "$mesh")
model_id=$(json_field id <<<"$model")
client/curl/wait-job.sh "$(json_field job_id <<<"$model")" >/dev/null
n=0
submit_embed() { n=$((n + 1)); client/curl/embed.sh "$model_id" --recipient "r$n-$RANDOM" | json_field job_id; }
submit_detect() { client/curl/detect.sh "$model_id" "$work/suspect.ply" | json_field job_id; }
latency_ms() {  # of a finished job
  local job; job=$(client/curl/wait-job.sh "$1")
  local created finished
  created=$(json_field created_at <<<"$job"); finished=$(json_field finished_at <<<"$job")
  echo $(( ($(date -d "$finished" +%s%N) - $(date -d "$created" +%s%N)) / 1000000 ))
}
median() { sort -n | awk '{ a[NR] = $1 } END { print (NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2) }'; }

# A marked copy, moved by a similarity transform, as the suspect.
first=$(submit_embed); latency_ms "$first" >/dev/null
client/curl/get-job-result.sh "$first" "$work/marked.obj"
build/client/meshmark attack similarity "$work/marked.obj" "$work/suspect.ply" --seed 5 >/dev/null
submit_detect | { read -r j; latency_ms "$j" >/dev/null; }  # warms the model's detection data

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); median of $runs"
for kind in embed detect; do
  single=(); busy=()
  for _ in $(seq "$runs"); do
    single+=("$(latency_ms "$(submit_$kind)")")
    a=$(submit_$kind); b=$(submit_$kind)
    busy+=("$(latency_ms "$a")" "$(latency_ms "$b")")
  done
  printf '%s job latency: alone %s ms, two at once %s ms\n' "$kind" \
    "$(printf '%s\n' "${single[@]}" | median)" "$(printf '%s\n' "${busy[@]}" | median)"
done
iso_ns() { date -d "$1" +%s%N; }
for kind in embed detect; do
  jobs=(); for _ in $(seq "$batch"); do jobs+=("$(submit_$kind)"); done
  first=""; last=0
  for j in "${jobs[@]}"; do
    job=$(client/curl/wait-job.sh "$j")
    created=$(iso_ns "$(json_field created_at <<<"$job")"); finished=$(iso_ns "$(json_field finished_at <<<"$job")")
    [[ -z "$first" || $created -lt $first ]] && first=$created
    ((finished > last)) && last=$finished
  done
  awk -v n="$batch" -v ns=$((last - first)) -v kind="$kind" 'BEGIN { printf "%s throughput: %d jobs at once, %.1f jobs/s\n", kind, n, n / (ns / 1e9) }'
done
