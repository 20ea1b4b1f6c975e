#!/usr/bin/env bash
# GET /livez — is the process up?
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/livez"
