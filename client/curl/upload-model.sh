#!/usr/bin/env bash
# POST /v1/models — upload an original mesh (raw body); answers 202 and the model (state preparing).
# Usage: upload-model.sh FILE [NAME]
. "$(dirname "$0")/common.sh"
file="$1"; name="${2:-$(basename "${file%.*}")}"; format="${file##*.}"
curl -sS -X POST "$SERVER/v1/models?format=$format&name=$name" -H "$(auth)" \
  -H "Content-Type: application/octet-stream" --data-binary "@$file"
