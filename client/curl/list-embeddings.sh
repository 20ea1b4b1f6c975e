#!/usr/bin/env bash
# GET /v1/models/{id}/embeddings — every copy handed out (payload, recipient, parameters).
# Usage: list-embeddings.sh MODEL_ID
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/v1/models/$1/embeddings" -H "$(auth)"
