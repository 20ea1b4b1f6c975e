#!/usr/bin/env bash
# GET /v1/jobs/{id} — state, progress, stage, result or error.
# Usage: get-job.sh JOB_ID
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/v1/jobs/$1" -H "$(auth)"
