#!/usr/bin/env bash
# Job throughput of 1, 2 and 3 daemons sharing one PostgreSQL store and one S3-compatible bucket
# (both started here on loopback), on this machine: every daemon shares its cores, so this shows
# the cost of the shared store and of claiming, not a cluster's capacity. For each N: EMBEDS embed
# jobs then DETECTS detect jobs on a prepared model (the bunny), submitted round-robin through the
# N daemons, all at once; throughput = jobs ÷ (last finished_at − first created_at), medians of
# RUNS. Every daemon has --workers 2.
# Usage: tests/load/cluster_bench.sh [RUNS] [EMBEDS] [DETECTS]     (from a built tree)
set -euo pipefail
cd "$(dirname "$0")/../.."
runs="${1:-3}"; embeds="${2:-40}"; detects="${3:-12}"
mesh="${MESHMARK_SHARED:-../shared}/meshes/bunny.obj"
work=$(mktemp -d); chmod 755 "$work"
pids=()
stop_daemons() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null || true; done; pids=(); }
cleanup() {
  stop_daemons
  deploy/postgres-test-server.sh "$work/pg" stop >/dev/null 2>&1 || true
  [[ -n "${s3_pid:-}" ]] && kill "$s3_pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
uri=$(deploy/postgres-test-server.sh "$work/pg")
read -r s3_endpoint s3_pid < <(deploy/s3-test-server.sh "$work/s3")
export MESHMARK_S3_ENDPOINT="$s3_endpoint" AWS_ACCESS_KEY_ID=S3RVER AWS_SECRET_ACCESS_KEY=S3RVER
export MESHMARK_ADMIN_TOKEN="cluster-bench-$RANDOM$RANDOM"
head -c 32 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$work/master.key"
chmod 600 "$work/master.key"
. client/curl/common.sh

servers=()
start_daemons() {  # N DATABASE
  local n=$1 database=$2
  psql -q "$uri" -c "CREATE DATABASE $database"
  servers=()
  for i in $(seq 0 $((n - 1))); do
    MESHMARK_DAEMON=build/server/meshmarkd deploy/start-daemon.sh --listen 127.0.0.1:0 --data "$work/$database-$i" \
      --store "${uri%/*}/$database" --blobs "s3://meshmark-test/$database" --master-key-file "$work/master.key" \
      --workers 2 --max-queue 256 --log-level warn >"$work/out-$database-$i" 2>"$work/log-$database-$i" &
    pids+=($!)
    for _ in $(seq 100); do grep -q "listening on" "$work/out-$database-$i" && break; sleep 0.1; done
    servers+=("$(grep -o "http://[0-9.:]*" "$work/out-$database-$i")")
  done
}
on() { local i=$1; shift; MESHMARK_SERVER="${servers[$((i % ${#servers[@]}))]}" "$@"; }
millis() { echo $(( $(date -d "$1" +%s%N) / 1000000 )); }
median() { sort -n | awk '{ a[NR] = $1 } END { print (NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2) }'; }

# Jobs per second of the jobs whose ids are on stdin (waited for through daemon 0).
throughput() {
  local first="" last=0 count=0 job created finished
  while read -r id; do
    job=$(on 0 client/curl/wait-job.sh "$id")
    [[ "$(json_field state <<<"$job")" == succeeded ]] || { echo "job $id: $job" >&2; exit 1; }
    created=$(millis "$(json_field created_at <<<"$job")"); finished=$(millis "$(json_field finished_at <<<"$job")")
    [[ -z "$first" || $created -lt $first ]] && first=$created
    (( finished > last )) && last=$finished
    count=$((count + 1))
  done
  awk -v n="$count" -v ms="$((last - first))" 'BEGIN { printf "%.2f\n", n * 1000 / ms }'
}

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); medians of $runs"
steal_before=$(awk '/^cpu /{print $9}' /proc/stat)
for n in 1 2 3; do
  embed_rates=(); detect_rates=()
  for run in $(seq "$runs"); do
    start_daemons "$n" "bench_${n}_$run"
    MESHMARK_TOKEN=$(on 0 client/curl/create-owner.sh bench | json_field api_key); export MESHMARK_TOKEN
    model=$(on 0 client/curl/upload-model.sh "$mesh")
    model_id=$(json_field id <<<"$model")
    on 0 client/curl/wait-job.sh "$(json_field job_id <<<"$model")" >/dev/null
    # Each daemon loads the prepared model once before the clock starts; the copy is the suspect.
    for i in $(seq 0 $((n - 1))); do
      on 0 client/curl/wait-job.sh "$(on "$i" client/curl/embed.sh "$model_id" --recipient "warm-$i" | json_field job_id)" \
        >"$work/warm.json"
    done
    on 0 client/curl/get-job-result.sh "$(json_field id <"$work/warm.json")" "$work/suspect.obj" >/dev/null
    for i in $(seq 0 $((n - 1))); do
      on 0 client/curl/wait-job.sh "$(on "$i" client/curl/detect.sh "$model_id" "$work/suspect.obj" | json_field job_id)" \
        >/dev/null
    done
    embed_rates+=("$(for k in $(seq "$embeds"); do
      on "$k" client/curl/embed.sh "$model_id" --recipient "r$k" | json_field job_id
    done | throughput)")
    detect_rates+=("$(for k in $(seq "$detects"); do
      on "$k" client/curl/detect.sh "$model_id" "$work/suspect.obj" | json_field job_id
    done | throughput)")
    stop_daemons
  done
  printf '%d daemon(s): embed %s jobs/s, detect %s jobs/s   (runs: embed %s; detect %s)\n' "$n" \
    "$(printf '%s\n' "${embed_rates[@]}" | median)" "$(printf '%s\n' "${detect_rates[@]}" | median)" \
    "${embed_rates[*]}" "${detect_rates[*]}"
done
steal_after=$(awk '/^cpu /{print $9}' /proc/stat)
echo "CPU steal during the runs: $((steal_after - steal_before)) ticks"
