#!/usr/bin/env bash
# POST /v1/owners — create an owner; prints {"owner_id", "api_key"} (the key is shown once).
# Usage: MESHMARK_ADMIN_TOKEN=... create-owner.sh [NAME]
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body -X POST "$SERVER/v1/owners" \
  -H "Authorization: Bearer ${MESHMARK_ADMIN_TOKEN:?set MESHMARK_ADMIN_TOKEN (the admin-token file in the data directory)}" \
  -H "Content-Type: application/json" -d "{\"name\": \"${1:-owner}\"}"
