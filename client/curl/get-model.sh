#!/usr/bin/env bash
# GET /v1/models/{id} — state (preparing, ready, failed) and validation report.
# Usage: get-model.sh MODEL_ID
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/v1/models/$1" -H "$(auth)"
