#!/usr/bin/env bash
# The Docker deployment, for real: builds deploy/Dockerfile exactly as the README says, runs the
# image, and checks what a user relies on: the curl walkthrough against the container (owner,
# upload, embed, download, detect naming the recipient), the health check turning healthy,
# `docker exec … meshmark`, the non-root user, a drain on `docker stop`, and a new container on
# the same volume that still has every model and copy. Prints the image's size and each step's
# time. Starts dockerd when none answers and stops it at the end; makes the base image locally
# when it is missing (deploy/docker-base.sh). Exits 77 (not run, with the reason) where this
# machine cannot run dockerd; 1 on a failure.
#   MESHMARK_DOCKER_MESH   the original to use (default: the example creature, written by the
#                          host build's meshmark, or build/client/meshmark)
set -euo pipefail
cd "$(dirname "$0")/.."
curl_dir="$PWD/client/curl"
name="meshmark-test-$$"
volume="meshmark-test-data-$$"
work=$(mktemp -d)
started_dockerd=""

say() { printf '[docker %5ds] %s\n' $((SECONDS)) "$*"; }
cleanup() {
  docker rm -f "$name" "$name-2" >/dev/null 2>&1 || true
  docker volume rm "$volume" >/dev/null 2>&1 || true
  if [[ -n "$started_dockerd" ]]; then
    kill "$started_dockerd" 2>/dev/null || true
    wait "$started_dockerd" 2>/dev/null || true
    say "stopped the dockerd this test started"
  fi
  rm -rf "$work"
}
trap cleanup EXIT
not_run() { echo "docker test not run: $*"; exit 77; }

deploy/install-deps.sh docker >/dev/null
if ! docker info >/dev/null 2>&1; then
  [[ $(id -u) -eq 0 ]] || not_run "no Docker engine answers and starting dockerd needs root"
  dockerd >"$work/dockerd.log" 2>&1 &
  started_dockerd=$!
  for _ in $(seq 60); do docker info >/dev/null 2>&1 && break; sleep 1; done
  if ! docker info >/dev/null 2>&1; then
    tail -n 5 "$work/dockerd.log"
    not_run "dockerd does not start on this machine (its last words above)"
  fi
  say "started dockerd $(docker version -f '{{.Server.Version}}')"
fi

deploy/docker-base.sh
docker-compose -f deploy/compose.yaml config -q || { echo "deploy/compose.yaml is not valid for docker-compose"; exit 1; }
say "deploy/compose.yaml: valid for $(docker-compose version --short 2>/dev/null | sed -n 1p | sed 's/^/docker-compose /')"
say "docker build -f deploy/Dockerfile -t meshmark ."
docker build -f deploy/Dockerfile -t meshmark . >"$work/build.log" 2>&1 || { tail -n 40 "$work/build.log"; exit 1; }
say "built: image $(docker image inspect -f '{{.Size}}' meshmark | awk '{ printf "%.0f MB", $1 / 1e6 }')"

mesh="${MESHMARK_DOCKER_MESH:-}"
if [[ -z "$mesh" ]]; then
  cli="$(command -v meshmark || echo build/client/meshmark)"
  [[ -x "$cli" ]] || cli=""
  if [[ -n "$cli" ]]; then mesh="$work/creature.obj"; "$cli" example creature "$mesh" >/dev/null
  else
    mesh="$work/creature.obj"
    docker run --rm --user root -v "$work:/out" --entrypoint meshmark meshmark example creature /out/creature.obj >/dev/null
  fi
fi

# Starts a container on the volume with a quick health interval (the check itself is the image's);
# prints its loopback URL once /livez answers.
start_container() {
  docker run -d --name "$1" -p 127.0.0.1::8080 -v "$volume:/data" --health-interval=2s meshmark >/dev/null
  local port url
  port=$(docker port "$1" 8080/tcp | sed -n 1p | awk -F: '{ print $NF }')
  url="http://127.0.0.1:$port"
  for _ in $(seq 100); do curl -fsS "$url/livez" >/dev/null 2>&1 && break; sleep 0.2; done
  curl -fsS "$url/livez" >/dev/null || { docker logs "$1"; return 1; }
  echo "$url"
}

wait_healthy() {
  local status=""
  for _ in $(seq 60); do
    status=$(docker inspect -f '{{.State.Health.Status}}' "$1")
    [[ "$status" == healthy ]] && return 0
    sleep 1
  done
  echo "health: $status"; docker inspect -f '{{json .State.Health}}' "$1"; return 1
}

url=$(start_container "$name")
say "container up at $url"
wait_healthy "$name"
say "health check: healthy (meshmark health inside the image)"
[[ $(docker exec "$name" id -u) == 10001 ]] || { echo "the daemon does not run as uid 10001"; exit 1; }
daemon_user=$(docker top "$name" -o pid,user,comm | awk '$3 == "meshmarkd" { print $2 }')
[[ -n "$daemon_user" && "$daemon_user" != root && "$daemon_user" != 0 ]] || { echo "meshmarkd runs as '$daemon_user'"; exit 1; }
say "runs as $(docker exec "$name" id -un) (uid 10001)"

admin=$(docker exec "$name" cat /data/admin-token)
export MESHMARK_SERVER="$url" MESHMARK_ADMIN_TOKEN="$admin"
output=$("$curl_dir/walkthrough.sh" "$mesh" "$work")
last=$(tail -1 <<<"$output")
grep -q '"detected":true' <<<"$last" && grep -q '"match":{[^}]*"recipient":"reseller-42"' <<<"$last" || {
  echo "$output"; echo "the walkthrough's detection did not name reseller-42"; exit 1; }
token=$(grep -o '"api_key":"[^"]*"' <<<"$output" | sed -n 1p | cut -d'"' -f4)
model=$(grep -o '"id":"mdl_[^"]*"' <<<"$output" | sed -n 1p | cut -d'"' -f4)
say "walkthrough: owner, upload, embed, download, detect named reseller-42 (model $model)"
# The page read whole first: `curl | grep -q` fails under pipefail when grep stops reading early.
page=$(curl -fsS "$url/") && grep -q '<script type="module" src="/console/app.js">' <<<"$page" &&
  curl -fsS "$url/console/vendor/three.module.js" >/dev/null || { echo "the image serves no web console at /"; exit 1; }
say "the web console is served at / (with three.js)"

docker exec "$name" meshmark owners list --server http://127.0.0.1:8080 --token "$admin" | grep 'studio-' >/dev/null || {
  echo "docker exec … meshmark owners list did not list the owner"; exit 1; }
say "docker exec $name meshmark owners list: works"

t0=$SECONDS
docker stop -t 60 "$name" >/dev/null
code=$(docker inspect -f '{{.State.ExitCode}}' "$name")
[[ "$code" == 0 ]] || { docker logs --tail 20 "$name"; echo "the daemon exited with $code on SIGTERM"; exit 1; }
docker logs "$name" 2>&1 | grep "draining" >/dev/null || { docker logs --tail 20 "$name"; echo "no drain in the logs"; exit 1; }
say "docker stop: drained and exited 0 in $((SECONDS - t0)) s"

url=$(start_container "$name-2")
export MESHMARK_SERVER="$url" MESHMARK_TOKEN="$token"
"$curl_dir/get-model.sh" "$model" | grep '"state":"ready"' >/dev/null || { echo "the model is gone after the restart"; exit 1; }
"$curl_dir/list-embeddings.sh" "$model" | grep '"recipient":"reseller-42"' >/dev/null || { echo "the copy is gone after the restart"; exit 1; }
detect=$("$curl_dir/detect.sh" "$model" "$work/marked.obj")
result=$("$curl_dir/wait-job.sh" "$(grep -o '"job_id":"[^"]*"' <<<"$detect" | cut -d'"' -f4)")
grep -q '"match":{[^}]*"recipient":"reseller-42"' <<<"$result" || { echo "$result"; echo "no match after the restart"; exit 1; }
say "a new container on the same volume: the model, its copy and the recipient's match are all there"
wait_healthy "$name-2"
docker stop -t 60 "$name-2" >/dev/null
say "passed"
