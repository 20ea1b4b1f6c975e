#!/usr/bin/env bash
# POST /v1/models/{id}/detect — check a suspect mesh (raw body: obj, off, ply, stl, glb, gltf, 3mf,
# or NAME.gltf.zip / NAME.obj.zip with companion files); answers 202 {"job_id"}.
# Usage: detect.sh MODEL_ID SUSPECT_FILE
. "$(dirname "$0")/common.sh"
need_file "${2:?usage: detect.sh MODEL_ID SUSPECT_FILE}"; file="$2"; format="$(format_of "$file")"
curl -sS --fail-with-body -X POST "$SERVER/v1/models/$1/detect?format=$format" -H "$(auth)" \
  -H "Content-Type: application/octet-stream" --data-binary "@$file"
