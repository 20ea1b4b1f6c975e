#!/usr/bin/env bash
# The README's curl walkthrough through nginx in front of three daemons on one PostgreSQL store
# and one S3-compatible bucket (the servers the test command started), then the same owner's
# models listed through each daemon alone. Exits 77 (skipped) without the servers or nginx.
# Usage: cluster_walkthrough_test.sh START_SCRIPT MESHMARKD CURL_DIR MESHMARK_CLI TEMPLATE
set -euo pipefail
start="$1"; daemon="$2"; curl_dir="$3"; cli="$4"; template="$5"
if [[ -z "${MESHMARK_TEST_POSTGRES:-}" || -z "${MESHMARK_TEST_S3_ENDPOINT:-}" ]] || ! command -v nginx >/dev/null; then
  echo "skipped: needs MESHMARK_TEST_POSTGRES, MESHMARK_TEST_S3_ENDPOINT and nginx"
  exit 77
fi
work=$(mktemp -d)
pids=()
cleanup() {
  [[ -f "$work/nginx.pid" ]] && kill "$(cat "$work/nginx.pid")" 2>/dev/null
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done
  rm -rf "$work"
}
trap cleanup EXIT
database="mm_walk_$(date +%s%N)"
psql -q "$MESHMARK_TEST_POSTGRES" -c "CREATE DATABASE $database"
store="${MESHMARK_TEST_POSTGRES%/*}/$database"
head -c 32 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$work/master.key"
chmod 600 "$work/master.key"
export MESHMARK_S3_ENDPOINT="$MESHMARK_TEST_S3_ENDPOINT" AWS_ACCESS_KEY_ID=S3RVER AWS_SECRET_ACCESS_KEY=S3RVER
export MESHMARK_ADMIN_TOKEN="cluster-walkthrough-admin-token-$RANDOM$RANDOM"
upstreams=""
for i in 0 1 2; do
  MESHMARK_DAEMON="$daemon" "$start" --listen 127.0.0.1:0 --data "$work/node$i" --store "$store" \
    --blobs "s3://meshmark-test/$database" --master-key-file "$work/master.key" \
    --max-connections-per-client 1024 >"$work/out$i" 2>"$work/log$i" &
  pids+=($!)
  for _ in $(seq 100); do grep -q "listening on" "$work/out$i" && break; sleep 0.1; done
  ports[$i]=$(grep -o "http://[0-9.:]*" "$work/out$i" | sed 's/.*://')
  upstreams+="server 127.0.0.1:${ports[$i]}; "
done
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
mkdir -p "$work/nginx"
sed -e "s/\${MESHMARK_UPSTREAMS}/$upstreams/" -e "s/\${MESHMARK_LISTEN}/127.0.0.1:$port/" "$template" >"$work/site.conf"
cat >"$work/nginx.conf" <<CONF
$( [[ $(id -u) -eq 0 ]] && echo "user root;" )
worker_processes 1;
pid $work/nginx.pid;
error_log $work/nginx/error.log;
events {}
http {
  access_log $work/nginx/access.log;
  client_body_temp_path $work/nginx/body;
  proxy_temp_path $work/nginx/proxy;
  fastcgi_temp_path $work/nginx/fastcgi;
  uwsgi_temp_path $work/nginx/uwsgi;
  scgi_temp_path $work/nginx/scgi;
  include $work/site.conf;
}
CONF
nginx -c "$work/nginx.conf" -p "$work/nginx"
for _ in $(seq 50); do curl -sf "http://127.0.0.1:$port/livez" >/dev/null && break; sleep 0.1; done
"$cli" example creature "$work/creature.obj"
mkdir -p "$work/walk"
export MESHMARK_SERVER="http://127.0.0.1:$port"
output=$("$curl_dir/walkthrough.sh" "$work/creature.obj" "$work/walk")
last=$(tail -1 <<<"$output")
grep -q '"state":"succeeded"' <<<"$last"
grep -q '"match":{[^}]*"recipient":"reseller-42"' <<<"$last"
# The owner and its model, made through nginx, are every daemon's.
served=0
key=$(grep -o '"api_key":"[^"]*"' <<<"$output" | head -1 | cut -d'"' -f4)
for i in 0 1 2; do
  models=$(curl -sf -H "Authorization: Bearer $key" "http://127.0.0.1:${ports[$i]}/v1/models")
  grep -q '"state":"ready"' <<<"$models" && served=$((served + 1))
done
[[ $served -eq 3 ]]
echo "cluster walkthrough: detection through nginx names reseller-42; the model is ready on all three daemons"
