#!/usr/bin/env bash
# GET /v1/jobs/{id}/report — a detection's evidence report, one self-contained HTML file.
# Usage: get-job-report.sh JOB_ID [OUT_FILE]   (default evidence-JOB_ID.html; curl exits 22 on an HTTP error)
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/v1/jobs/$1/report" -H "$(auth)" -o "${2:-evidence-$1.html}"
