#!/usr/bin/env bash
# GET /openapi.json — the API description.
. "$(dirname "$0")/common.sh"
curl -sS "$SERVER/openapi.json"
