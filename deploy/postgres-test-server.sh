#!/usr/bin/env bash
# Starts a throwaway PostgreSQL server for the store tests — Debian's PostgreSQL 15, a new
# cluster in FOLDER (trust authentication, loopback only, fsync off: its data is thrown away) — on
# a free port. Prints its URI (database postgres) once it accepts connections; `deploy/postgres-test-server.sh
# FOLDER stop` stops it. As root, the server runs as the postgres user (it refuses root).
# `… FOLDER restart` restarts it (fast shutdown: every connection is cut), as the tests do.
# Usage: deploy/postgres-test-server.sh FOLDER [stop|restart]
set -euo pipefail
folder=${1:?usage: deploy/postgres-test-server.sh FOLDER [stop|restart]}
bin=$(ls -d /usr/lib/postgresql/*/bin | sort -V | tail -1)
as_server() {
  if [[ $(id -u) -eq 0 ]]; then runuser -u postgres -- "$@"; else "$@"; fi
}
if [[ "${2:-}" == stop ]]; then
  as_server "$bin/pg_ctl" -D "$folder/data" -m immediate stop >/dev/null 2>&1 || true
  exit 0
fi
if [[ "${2:-}" == restart ]]; then
  as_server "$bin/pg_ctl" -D "$folder/data" -l "$folder/log" -m fast -w restart >/dev/null
  exit 0
fi
mkdir -p "$folder"
if [[ $(id -u) -eq 0 ]]; then
  chown postgres: "$folder"
  chmod o+x "$(dirname "$folder")"  # the server's user must reach its folder (a mktemp -d is 0700)
fi
as_server "$bin/initdb" -D "$folder/data" -U postgres --auth=trust -E UTF8 --locale=C >"$folder/initdb.log" 2>&1 ||
  { cat "$folder/initdb.log" >&2; exit 1; }
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
as_server "$bin/pg_ctl" -D "$folder/data" -l "$folder/log" -w -t 60 \
  -o "-p $port -k $folder -c listen_addresses=127.0.0.1 -c fsync=off -c synchronous_commit=off -c full_page_writes=off -c max_connections=300" \
  start >/dev/null || { cat "$folder/log" >&2; exit 1; }
echo "postgresql://postgres@127.0.0.1:$port/postgres"
