#!/usr/bin/env bash
# GET /livez — is the process up?
. "$(dirname "$0")/common.sh"
curl -sS "$SERVER/livez"
