#!/usr/bin/env bash
# Polls GET /v1/jobs/{id} until the job finishes; prints the final job.
# Usage: wait-job.sh JOB_ID
. "$(dirname "$0")/common.sh"
while :; do
  job=$(curl -sS --fail-with-body "$SERVER/v1/jobs/$1" -H "$(auth)")
  case "$job" in *"\"state\":\"queued\""*|*"\"state\":\"running\""*) sleep 0.5 ;; *) echo "$job"; break ;; esac
done
