#!/usr/bin/env bash
# Daemon job latency on a prepared model (the bunny): embed and detect jobs, one at a time and
# two at once (both cores busy, 2 workers). Latency = finished_at − created_at as the daemon
# records them (queueing included); medians of RUNS. Then throughput: BATCH jobs of each kind
# submitted at once, jobs ÷ (last finished_at − first created_at).
# Usage: tests/load/job_latency.sh [RUNS] [BATCH]        (from a built tree)
set -euo pipefail
cd "$(dirname "$0")/../.."
runs="${1:-5}"; batch="${2:-30}"
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
# Throughput: BATCH jobs sent by one curl over one connection (a process per request would cap
# the rate below the daemon's and take its cores), the client then idle but for polling the last
# job; jobs ÷ (last finished_at − first created_at), as the daemon recorded them. Embeds in each
# output format the upload allows (the OBJ kept whole, or plain meshes), then detections.
iso_ns() { date -d "$1" +%s%N; }
request() {  # one request of a curl config: METHOD PATH [BODY | @FILE]
  echo "request = \"$1\""; echo "url = \"$MESHMARK_SERVER$2\""; echo "header = \"$(auth)\""
  if [[ "${3:-}" == @* ]]; then echo "data-binary = \"$3\""; echo 'header = "Content-Type: application/octet-stream"'
  elif [[ -n "${3:-}" ]]; then echo "data = \"${3//\"/\\\"}\""; echo 'header = "Content-Type: application/json"'; fi
}
throughput() {  # LABEL, then the requests' config on standard input
  local label=$1 answers jobs=() first="" last=0
  answers=$(curl -sS --fail-with-body -K - -w '\n')
  mapfile -t jobs < <(grep -o '"job_id":"[^"]*"' <<<"$answers" | cut -d'"' -f4)
  ((${#jobs[@]} == batch)) || { echo "$label: ${#jobs[@]} of $batch jobs accepted: $answers" >&2; exit 1; }
  while :; do
    state=$(curl -sS "$MESHMARK_SERVER/v1/jobs/${jobs[-1]}" -H "$(auth)" | json_field state)
    [[ $state == succeeded || $state == failed || $state == canceled ]] && break
    sleep 0.2
  done
  for j in "${jobs[@]}"; do
    job=$(client/curl/wait-job.sh "$j")
    [[ $(json_field state <<<"$job") == succeeded ]] || { echo "$label: job $j did not succeed: $job" >&2; exit 1; }
    created=$(iso_ns "$(json_field created_at <<<"$job")"); finished=$(iso_ns "$(json_field finished_at <<<"$job")")
    [[ -z "$first" || $created -lt $first ]] && first=$created
    ((finished > last)) && last=$finished
  done
  awk -v n="$batch" -v ns=$((last - first)) -v label="$label" \
    'BEGIN { printf "%s throughput: %d jobs at once, %.1f jobs/s\n", label, n, n / (ns / 1e9) }'
}
for format in obj off ply stl; do
  for i in $(seq "$batch"); do
    ((i > 1)) && echo next
    request POST "/v1/models/$model_id/embed" "{\"recipient\": \"$format-$i-$RANDOM\", \"format\": \"$format\"}"
  done | throughput "embed ($format out)"
done
for i in $(seq "$batch"); do
  ((i > 1)) && echo next
  request POST "/v1/models/$model_id/detect?format=ply" "@$work/suspect.ply"
done | throughput detect
