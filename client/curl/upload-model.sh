#!/usr/bin/env bash
# POST /v1/models — upload an original mesh (raw body); answers 202 and the model (state preparing).
# Usage: upload-model.sh FILE [NAME]
. "$(dirname "$0")/common.sh"
need_file "${1:?usage: upload-model.sh FILE [NAME]}"; file="$1"; name="${2:-$(basename "${file%.*}")}"; format="${file##*.}"
curl -sS --fail-with-body -X POST "$SERVER/v1/models" --url-query "format=$format" --url-query "name=$name" -H "$(auth)" \
  -H "Content-Type: application/octet-stream" --data-binary "@$file"
