#!/usr/bin/env bash
# GET /v1/jobs/{id}/result — the watermarked mesh (embed jobs) or the detection (detect jobs).
# Usage: get-job-result.sh JOB_ID [OUT_FILE]
. "$(dirname "$0")/common.sh"
if [[ -n "${2:-}" ]]; then curl -sS -f "$SERVER/v1/jobs/$1/result" -H "$(auth)" -o "$2"; else curl -sS "$SERVER/v1/jobs/$1/result" -H "$(auth)"; fi
