#!/usr/bin/env bash
# GET /v1/models — your models.
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/v1/models" -H "$(auth)"
