#!/usr/bin/env bash
# POST /v1/models/{id}/embed — make a watermarked copy; answers 202 {"job_id", "payload", ...}.
# Usage: embed.sh MODEL_ID PAYLOAD_HEX          (a payload of your choice)
#        embed.sh MODEL_ID --recipient NAME     (the daemon assigns a unique payload)
#   MESHMARK_REQUESTED_BY  optional: who asked for the copy (kept with its record)
. "$(dirname "$0")/common.sh"
if [[ "${2:-}" == "--recipient" ]]; then body="\"recipient\": $(json_string "$3")"; else body="\"payload\": $(json_string "$2")"; fi
if [[ -n "${MESHMARK_REQUESTED_BY:-}" ]]; then body+=", \"requested_by\": $(json_string "$MESHMARK_REQUESTED_BY")"; fi
curl -sS --fail-with-body -X POST "$SERVER/v1/models/$1/embed" -H "$(auth)" -H "Content-Type: application/json" -d "{$body}"
