#!/usr/bin/env bash
# DELETE /v1/jobs/{id} — cancel a queued or running job.
# Usage: cancel-job.sh JOB_ID
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body -X DELETE "$SERVER/v1/jobs/$1" -H "$(auth)"
