#!/usr/bin/env bash
# GET /readyz — ready to take work (store answers, not shutting down)?
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/readyz"
