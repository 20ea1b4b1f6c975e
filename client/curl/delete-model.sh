#!/usr/bin/env bash
# DELETE /v1/models/{id} — delete a model, its files and recorded embeddings. Refused (409) while
# copies of it were handed out: they could never be traced again. --force confirms.
# Usage: delete-model.sh MODEL_ID [--force]
. "$(dirname "$0")/common.sh"
confirm=""; [[ "${2:-}" == "--force" ]] && confirm="?confirm=$1"
curl -sS --fail-with-body -X DELETE "$SERVER/v1/models/$1$confirm" -H "$(auth)" -w "%{http_code}\n"
