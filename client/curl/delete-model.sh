#!/usr/bin/env bash
# DELETE /v1/models/{id} — delete a model, its files and recorded embeddings.
# Usage: delete-model.sh MODEL_ID
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body -X DELETE "$SERVER/v1/models/$1" -H "$(auth)" -w "%{http_code}\n"
