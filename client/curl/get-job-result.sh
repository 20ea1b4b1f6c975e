#!/usr/bin/env bash
# GET /v1/jobs/{id}/result — the watermarked mesh (embed jobs) or the detection (detect jobs).
# Usage: get-job-result.sh JOB_ID [OUT_FILE]   (curl exits 22 and prints the problem on an HTTP error)
. "$(dirname "$0")/common.sh"
if [[ -n "${2:-}" ]]; then curl -sS --fail-with-body "$SERVER/v1/jobs/$1/result" -H "$(auth)" -o "$2"; else curl -sS --fail-with-body "$SERVER/v1/jobs/$1/result" -H "$(auth)"; fi
