#!/usr/bin/env bash
# The job queue's claim path on both stores: 10,000 no-op jobs claimed by 32 workers
# (meshmark_queue_bench), on SQLite and on a throwaway PostgreSQL started here on loopback
# (deploy/postgres-test-server.sh). Prints the figures, the machine and its CPU steal.
# Usage: tests/load/queue_bench.sh [BUILD_DIR] [JOBS] [WORKERS]
set -euo pipefail
cd "$(dirname "$0")/../.."
build="${1:-build}"; jobs="${2:-10000}"; workers="${3:-32}"
work=$(mktemp -d)
trap 'deploy/postgres-test-server.sh "$work/pg" stop; rm -rf "$work"' EXIT
uri=$(deploy/postgres-test-server.sh "$work/pg")
psql -q "$uri" -c "CREATE DATABASE queue_bench"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
steal_before=$(awk '/^cpu /{print $9}' /proc/stat)
"$build/tests/meshmark_queue_bench" "sqlite:$work/queue.db" "$jobs" "$workers"
"$build/tests/meshmark_queue_bench" "${uri%/*}/queue_bench" "$jobs" "$workers"
steal_after=$(awk '/^cpu /{print $9}' /proc/stat)
echo "CPU steal during the runs: $((steal_after - steal_before)) ticks"
