#!/usr/bin/env bash
# POST /v1/models — upload an original mesh or asset (raw body: obj, off, ply, stl, glb, gltf, 3mf, or
# NAME.gltf.zip / NAME.obj.zip holding the file and its companions); answers 202 and the model.
# Usage: upload-model.sh FILE [NAME]
. "$(dirname "$0")/common.sh"
need_file "${1:?usage: upload-model.sh FILE [NAME]}"; file="$1"; format="$(format_of "$file")"
base="$(basename "$file")"; name="${2:-${base%%.*}}"
curl -sS --fail-with-body -X POST "$SERVER/v1/models" --url-query "format=$format" --url-query "name=$name" -H "$(auth)" \
  -H "Content-Type: application/octet-stream" --data-binary "@$file"
