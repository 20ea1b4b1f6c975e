#!/usr/bin/env bash
# GET /openapi.json — the API description.
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/openapi.json"
